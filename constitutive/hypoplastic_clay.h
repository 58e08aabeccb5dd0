// Mašín (2005) hypoplastic model for clays, SPEC §6.1:
//   T̊ = f_s 𝕃:D + f_s f_d N ‖D‖,   ė = (1 + e) tr D,
// with the Matsuoka–Nakai critical state, the isotropic NCL
// ln(1+e) = N − λ* ln(p/p_r) and the asymptotic state boundary surface of
// Mašín & Herle (2005): f_d^SBS = ‖f_s 𝔸⁻¹:N‖⁻¹, 𝔸 = f_s 𝕃 + (1/λ*) T⊗1,
// asymptotic stretching D̂ ∝ −𝔸⁻¹:N.
// Source: D. Mašín, A hypoplastic constitutive model for clays, IJNAMG 29 (2005)
// 311–336; Mašín & Herle, Computers and Geotechnics 32 (2005) 400–410.
#pragma once

#include <string>

#include "constitutive/constitutive_model.h"

namespace granasym {

class HypoplasticClay : public ConstitutiveModel {
 public:
  struct Parameters {
    double critical_friction_angle = 0.0;  // φ_c (rad)
    double lambda_star = 0.0;              // λ*, slope of the NCL in ln(1+e)–ln p
    double kappa_star = 0.0;               // κ*, slope of isotropic unloading
    double n_intercept = 0.0;              // N = ln(1+e) on the NCL at p = p_r
    double bulk_shear_ratio = 0.0;         // r = K/G on the isotropic NCL
    double reference_pressure = 1.0;       // p_r (kPa)
    // Below this mean stress (kPa) the state counts as outside the model's
    // domain (the formulas hold for p > 0 only); integrators then cut the step.
    double minimum_mean_stress = 1e-9;
    // Names the first offending field (and the derived constant it breaks).
    bool IsValid(std::string* why) const;
    // London clay, Mašín (2005) Table 2: the project's reference set.
    static Parameters LondonClay();
  };

  // The parameters must be valid (GRANASYM_CHECK).
  explicit HypoplasticClay(const Parameters& parameters);

  ModelKind kind() const override { return ModelKind::kHypoplasticClay; }
  bool Rate(const ModelState& state, const Vector6& stretching, ModelRate* rate, Matrix6* tangent,
            std::string* why) const override;
  bool Jacobian(const ModelState& state, const Vector6& stretching, RateJacobian* jacobian,
                std::string* why) const override;
  bool IsAdmissible(const ModelState& state, std::string* why) const override;
  bool IsAdmissibleStart(const ModelState& state, std::string* why) const override;
  double EquivalentPressure(double void_ratio) const override;
  double VoidRatioForOcr(double mean_stress, double ocr) const override;
  ModelState MakeState(const Vector6& stress, double void_ratio) const override;
  bool ScaleState(double factor, ModelState* state) const override;
  // Normal stresses strictly compressive (necessary for a negative-definite T).
  void SignConstraints(Vector6* stress_codes, Eigen::VectorXd* internal_codes) const override;
  // On the ASBS (AsymptoteForStress below; asymptotic_states.h).
  bool AsymptoteOfStressDirection(double psi_sigma, double* psi_epsilon, double* ln_ocr,
                                  std::string* why) const override;
  double critical_friction_angle() const override { return parameters_.critical_friction_angle; }
  std::string Describe() const override;

  // The pieces of the rate at a state: T̊ = f_s 𝕃:D + f_s f_d N ‖D‖.
  struct Terms {
    double barotropy = 0.0;               // f_s (kPa)
    double pyknotropy = 0.0;              // f_d
    Matrix6 linear = Matrix6::Zero();     // 𝕃 as a matrix acting on D
    Vector6 nonlinear = Vector6::Zero();  // N
  };
  bool EvaluateTerms(const ModelState& state, Terms* terms, std::string* why) const;

  // The asymptotic state (ASBS) belonging to a stress direction.
  struct Asymptote {
    Vector6 stretching_direction = Vector6::Zero();  // D̂, unit norm, tension positive
    double pyknotropy_sbs = 0.0;                     // f_d^SBS
    double ocr = 0.0;                                // p_e/p = 2 (f_d^SBS)^(−1/α)
  };
  // Only the direction of `stress` matters (tension positive, compressive).
  bool AsymptoteForStress(const Vector6& stress, Asymptote* asymptote, std::string* why) const;

  const Parameters& parameters() const { return parameters_; }
  double a() const { return a_; }          // a = √3 (3 − sin φ_c)/(2√2 sin φ_c)
  double alpha() const { return alpha_; }  // α of f_d = (2p/p_e)^α

 private:
  Parameters parameters_;
  double a_ = 0.0;
  double alpha_ = 0.0;
  double c1_ = 0.0;
  double c2_ = 0.0;
  double barotropy_denominator_ = 0.0;  // 3 + a² − 2^α √3 a
};

}  // namespace granasym
