// von Wolffersdorff (1996) hypoplastic model for sands, SPEC §6.3, in
// Niemunis' standard form (tension positive, p = −tr T/3):
//   T̊ = f_b f_e/(T̂:T̂) [F² D + a² T̂ (T̂:D) + f_d a F (T̂ + T̂*) ‖D‖],   ė = (1 + e) tr D,
//   T̂ = T/tr T, T̂* = T̂ − 1/3, a = √3 (3 − sin φ_c)/(2√2 sin φ_c),
//   F = sqrt(tan²ψ/8 + (2 − tan²ψ)/(2 + √2 tanψ cos3θ)) − tanψ/(2√2),
//   tanψ = √3 ‖T̂*‖, cos3θ = −√6 tr(T̂*³)/(T̂*:T̂*)^{3/2},
// with Bauer's compression law e_{i,c,d} = e_{i0,c0,d0} exp[−(3p/h_s)^n] for the
// loosest, critical and densest void ratios and
//   f_e = (e_c/e)^β,  f_d = ((e − e_d)/(e_c − e_d))^α,
//   f_b = (h_s/n) (1 + e_i)/e_i (e_i0/e_c0)^β (3p/h_s)^{1−n}
//         [3 + a² − a√3 ((e_i0 − e_d0)/(e_c0 − e_d0))^α]⁻¹.
// f_b is chosen so that isotropic compression at e = e_i follows e_i(p)
// exactly; at f_d = 1 (e = e_c) the stationary stress ratios lie on the
// Matsuoka–Nakai cone of φ_c (the critical state, with e = e_c(p)).
//
// Equivalent pressure and OCR (SPEC §3, Eq. 2): p_e is the mean stress at which
// the isotropic limit line e_i(p) passes through the current e,
//   p_e = (h_s/3) [ln(e_i0/e)]^{1/n}   (0 for e ≥ e_i0),  OCR = p_e/p.
// e_i is this model's isotropic normal compression line: f_b is built so that
// isotropic compression at e = e_i stays on it (to 1e-11 in e, integrated), and
// isotropic compression from denser or looser states converges to e_i itself,
// not to a line parallel to it: |ln OCR| falls monotonically, from p = 10 to
// 3e5 kPa OCR 3 → 1.029, 30 → 1.13, 0.5 → 0.986 (HypoplasticSand.Isotropic*
// tests). So p_e* of SPEC §3 is measured from e_i, as the clay's from its NCL.
// Unlike the clay, the critical-state OCR is not a constant (e_c/e_i is, but
// the lines are not parallel in ln(1+e)–ln p: OCR_c = 4.1 at p = 1 MPa).
// The model is not homogeneous in p, so ScaleState is not available and there
// is no analytic asymptotic state boundary surface. Integrated asymptotes
// exist for isochoric paths (the critical state); along proportional paths
// with volume change Bauer's law drives e → 0 (p → ∞) in compression and p → 0
// in extension within a finite strain, before the stress ratio and OCR become
// stationary.
//
// Sources: P.-A. von Wolffersdorff, A hypoplastic relation for granular materials
// with a predefined limit state surface, Mech. Cohes.-Frict. Mater. 1 (1996)
// 251–271; E. Bauer, Calibration of a comprehensive hypoplastic model for
// granular materials, Soils Found. 36 (1996) 13–26; A. Niemunis, Extended
// hypoplastic models for soils, Habilitation, Bochum (2003); I. Herle and
// G. Gudehus, Determination of parameters of a hypoplastic constitutive model
// from properties of grain assemblies, Mech. Cohes.-Frict. Mater. 4 (1999)
// 461–486 (the Hochstetten sand set below). The formulas were checked against
// two public implementations (the soilmodels.com UMAT of Tamagnini, Sellari,
// Mašín and von Wolffersdorff; COFS-UWA/MPM3D sand_hypoplasticity.cpp) and the
// Hochstetten set against its quotation in the OpenSees UMAT documentation.
#pragma once

#include <string>

#include "constitutive/constitutive_model.h"

namespace granasym {

class HypoplasticSand : public ConstitutiveModel {
 public:
  struct Parameters {
    double critical_friction_angle = 0.0;  // φ_c (rad)
    double granular_hardness = 0.0;        // h_s (kPa)
    double compression_exponent = 0.0;     // n of Bauer's law, in (0, 1)
    double densest_void_ratio0 = 0.0;      // e_d0, at p = 0
    double critical_void_ratio0 = 0.0;     // e_c0, at p = 0
    double loosest_void_ratio0 = 0.0;      // e_i0, at p = 0
    double pyknotropy_exponent = 0.0;      // α of f_d
    double stiffness_exponent = 0.0;       // β of f_e (and of f_b)
    // Below this mean stress (kPa) the state counts as outside the model's
    // domain (f_b ∝ p^{1−n} vanishes at p = 0); integrators then cut the step.
    double minimum_mean_stress = 1e-9;
    // Names the first offending field (and, for the ordering, both fields).
    bool IsValid(std::string* why) const;
    // Hochstetten sand, Herle & Gudehus (1999): φ_c = 33°, h_s = 1000 MPa,
    // n = 0.25, e_d0 = 0.55, e_c0 = 0.95, e_i0 = 1.05, α = 0.25, β = 1.5.
    static Parameters HochstettenSand();
  };

  // The parameters must be valid (GRANASYM_CHECK).
  explicit HypoplasticSand(const Parameters& parameters);

  ModelKind kind() const override { return ModelKind::kHypoplasticSand; }
  bool Rate(const ModelState& state, const Vector6& stretching, ModelRate* rate, Matrix6* tangent,
            std::string* why) const override;
  bool Jacobian(const ModelState& state, const Vector6& stretching, RateJacobian* jacobian,
                std::string* why) const override;
  // Finite stress, p above minimum_mean_stress, all principal stresses
  // compressive (F is singular where a principal stress vanishes in triaxial
  // compression), and e_d(p) < e (f_d is not real below e_d).
  bool IsAdmissible(const ModelState& state, std::string* why) const override;
  bool IsAdmissibleStart(const ModelState& state, std::string* why) const override;
  // p_e on the isotropic limit line e_i (file comment); 0 for e ≥ e_i0.
  double EquivalentPressure(double void_ratio) const override;
  // e_i(ocr·p): the void ratio whose p_e is ocr·p.
  double VoidRatioForOcr(double mean_stress, double ocr) const override;
  ModelState MakeState(const Vector6& stress, double void_ratio) const override;
  // Not homogeneous in p (Bauer's law has the scale h_s): no rescaling.
  bool ScaleState(double factor, ModelState* state) const override { return false; }
  // Normal stresses strictly compressive; no internal variables.
  void SignConstraints(Vector6* stress_codes, Eigen::VectorXd* internal_codes) const override;
  double critical_friction_angle() const override { return parameters_.critical_friction_angle; }
  std::string Describe() const override;

  // Bauer's law at mean stress p (kPa): e_i, e_c, e_d.
  struct LimitVoidRatios {
    double loosest = 0.0;   // e_i
    double critical = 0.0;  // e_c
    double densest = 0.0;   // e_d
  };
  LimitVoidRatios LimitVoidRatiosAt(double mean_stress) const;

  // The pieces of the rate at a state:
  //   T̊ = f_b f_e (𝕃:D + f_d N ‖D‖),  𝕃 = (F² 𝕀 + a² T̂⊗T̂)/(T̂:T̂),  N = a F (T̂ + T̂*)/(T̂:T̂).
  struct Terms {
    double barotropy = 0.0;               // f_b (kPa)
    double density = 0.0;                 // f_e
    double pyknotropy = 0.0;              // f_d
    double lode_factor = 0.0;             // F
    Matrix6 linear = Matrix6::Zero();     // 𝕃 as a matrix acting on D
    Vector6 nonlinear = Vector6::Zero();  // N
  };
  bool EvaluateTerms(const ModelState& state, Terms* terms, std::string* why) const;

  const Parameters& parameters() const { return parameters_; }
  double a() const { return a_; }  // a = √3 (3 − sin φ_c)/(2√2 sin φ_c)
  // 3 + a² − a√3 ((e_i0 − e_d0)/(e_c0 − e_d0))^α, the denominator of f_b.
  double barotropy_denominator() const { return barotropy_denominator_; }

 private:
  Parameters parameters_;
  double a_ = 0.0;
  double barotropy_denominator_ = 0.0;
};

}  // namespace granasym
