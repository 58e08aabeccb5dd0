// Modified Cam clay, SPEC §6.2, in rate form (compression positive p, q):
//   f = q² + M² p (p − p_c),  associated flow D^p = λ̇ ∂f/∂T,
//   K = p/κ*, G = 3K(1 − 2ν)/(2(1 + ν)) or constant G,
//   ṗ_c/p_c = ε̇_v^p/(λ* − κ*),  NCL ln(1+e) = N − λ* ln(p/p_r),
// and the classical e–ln p form (λ, κ, e_N) where λ* = λ/(1+e), κ* = κ/(1+e).
// Both forms are exactly integrable along any path:
//   ln(1+e) = N − λ* ln(p_c/p_r) + κ* ln(p_c/p)   (or e = e_N − λ ln(p_c/p_r) + κ ln(p_c/p)),
// which fixes p_c from (p, e); on the CSL p = p_c/2, so OCR_c = 2^((λ−κ)/λ).
// Asymptotic states (log-log form, Poisson-ratio elasticity): on the Roscoe
// surface (ψ_σ ↔ η = q/p, p_c/p = 1 + η²/M²) proportional stretching keeps η
// and moves p and p_c together, so
//   ε̇_v ∝ λ*(M² − η²),  ε̇_s ∝ η[κ* c (M² − η²) + 2(λ* − κ*)],  c = 2(1+ν)/(9(1−2ν)),
//   tan ψ_ε = (3/√2) ε̇_s/ε̇_v,  ln OCR = (1 − κ*/λ*) ln(1 + η²/M²).
// Source: Roscoe & Burland (1968); Wood, Soil behaviour and critical state soil mechanics (1990).
#pragma once

#include <string>

#include "common/enum_names.h"
#include "constitutive/constitutive_model.h"

namespace granasym {

class ModifiedCamClay : public ConstitutiveModel {
 public:
  enum class CompressionForm { kLogLog, kSemiLog };
  enum class Elasticity { kPoissonRatio, kConstantShearModulus };

  struct Parameters {
    // kLogLog: lambda = λ*, kappa = κ*, n_intercept = N = ln(1+e) at p_r.
    // kSemiLog: lambda = λ, kappa = κ, n_intercept = e_N = e at p_r.
    CompressionForm form = CompressionForm::kLogLog;
    double critical_state_ratio = 0.0;  // M = q/p at critical state (compression)
    double lambda = 0.0;
    double kappa = 0.0;
    double n_intercept = 0.0;
    Elasticity elasticity = Elasticity::kPoissonRatio;
    double poisson_ratio = 0.25;        // ν, used with kPoissonRatio
    double shear_modulus = 0.0;         // G (kPa), used with kConstantShearModulus
    double reference_pressure = 1.0;    // p_r (kPa)
    double minimum_mean_stress = 1e-9;  // kPa; below this the state is inadmissible
    // A state counts as on the yield surface when f ≥ −yield_tolerance (M p_c)²;
    // the stress-point algorithms also use it as their drift tolerance.
    double yield_tolerance = 1e-9;
    // Rate form only (used by the ODE integrators): plastic flow where the
    // state lies on or within the band f ≥ −rate_form_band (M p_c)² and the
    // multiplier is positive, with a Baumgarte term in the multiplier,
    // λ̇ = (n:𝔼:D + β f ‖D‖)/(n:𝔼:n + H), so that ḟ = −β f ‖D‖ pulls
    // integration drift back onto f = 0 (β per unit strain); on f = 0 the term
    // vanishes and the exact plastic rate is unchanged. Its cost is yielding
    // up to 1e-4 (M p_c)² early (stresses within ~5e-5 of the surface).
    //
    // The element-test driver holds a branch over each piece of integration
    // (ModelState::branch, chosen by Branch): the elastic one until the state
    // reaches the band while loading, the plastic one (flowing whenever the
    // loading is positive, elastic otherwise, so its rate is continuous)
    // until the loading turns negative (Switches). Deciding the branch at
    // every evaluation instead (kAutoBranch) mixes the branches within one
    // step: the stage states of a Runge–Kutta step leave a curved yield
    // surface by O(h²), far more than the band, and a stage below the band
    // turns elastic, an error that the step's error estimate does not see
    // (issue 36 §5: ERK 5 on ψ_ε = 100° had errors of 1e-3 at rtol 1e-5).
    double rate_form_band = 1e-4;
    double drift_stabilization = 100.0;
    bool IsValid(std::string* why) const;
    // M = 0.9, ν = 0.25 and the NCL of London clay (λ* = 0.11, κ* = 0.016,
    // N = 1.375): the Cam clay counterpart of HypoplasticClay's reference set.
    static Parameters LondonClayNcl();
  };

  explicit ModifiedCamClay(const Parameters& parameters);

  ModelKind kind() const override { return ModelKind::kModifiedCamClay; }
  int num_internal() const override { return 1; }
  std::vector<std::string> internal_names() const override { return {"preconsolidation_kpa"}; }
  bool Rate(const ModelState& state, const Vector6& stretching, ModelRate* rate, Matrix6* tangent,
            std::string* why) const override;
  bool Jacobian(const ModelState& state, const Vector6& stretching, RateJacobian* jacobian,
                std::string* why) const override;
  bool IsAdmissible(const ModelState& state, std::string* why) const override;
  // Admissible and inside the yield surface (by yield_tolerance).
  bool IsAdmissibleStart(const ModelState& state, std::string* why) const override;
  double EquivalentPressure(double void_ratio) const override;
  double VoidRatioForOcr(double mean_stress, double ocr) const override;
  ModelState MakeState(const Vector6& stress, double void_ratio) const override;
  bool ScaleState(double factor, ModelState* state) const override;  // log-log form only
  // The branches of the rate form (ModelState::branch; see rate_form_band).
  static constexpr int kElasticBranch = 0;
  static constexpr int kPlasticBranch = 1;
  // Plastic on or within the band while loading, else elastic.
  int Branch(const ModelState& state, const Vector6& stretching) const override;
  // One switch, positive while the state's branch holds: on the plastic
  // branch the loading over (M p_c)² ‖D‖, on the elastic one (and kAutoBranch)
  // −min(f/(M p_c)² + rate_form_band, that loading), zero where the state
  // reaches the band while loading.
  int num_switches() const override { return 1; }
  void Switches(const ModelState& state, const Vector6& stretching, double* values) const override;
  // p_c > 0 (single normal stresses may be tensile at high OCR).
  void SignConstraints(Vector6* stress_codes, Eigen::VectorXd* internal_codes) const override;
  // The closed form of the file comment (log-log form, Poisson-ratio elasticity only).
  bool AsymptoteOfStressDirection(double psi_sigma, double* psi_epsilon, double* ln_ocr,
                                  std::string* why) const override;
  double critical_friction_angle() const override;
  std::string Describe() const override;

  // Pieces used by the stress-point algorithms (tension-positive stress, kPa).
  double YieldFunction(const Vector6& stress, double preconsolidation) const;   // kPa²
  Vector6 YieldGradient(const Vector6& stress, double preconsolidation) const;  // ∂f/∂T
  // ∂f/∂p_c = −M² p.
  double YieldGradientPreconsolidation(const Vector6& stress) const;
  // Tangent elastic stiffness 𝔼 (matrix acting on D) at a stress and void ratio.
  Matrix6 ElasticStiffness(const Vector6& stress, double void_ratio) const;
  // Effective λ*, κ* at a void ratio (the semi-log form divides by 1 + e).
  void CompressionSlopes(double void_ratio, double* lambda_star, double* kappa_star) const;
  // p_c on the elastic line through (p, e), see the file comment.
  double PreconsolidationFromElasticLine(double mean_stress, double void_ratio) const;
  // Whether the state is on or outside the yield surface by the tolerance.
  bool OnYieldSurface(const Vector6& stress, double preconsolidation) const;

  const Parameters& parameters() const { return parameters_; }

 private:
  Parameters parameters_;
};

template <>
struct EnumNames<ModifiedCamClay::CompressionForm> {
  static constexpr EnumEntry<ModifiedCamClay::CompressionForm> kEntries[] = {
      {ModifiedCamClay::CompressionForm::kLogLog, "log_log", "ln(1+e)-ln p: lambda*, kappa*, N"},
      {ModifiedCamClay::CompressionForm::kSemiLog, "semi_log", "e-ln p: lambda, kappa, e_N"},
  };
};

}  // namespace granasym
