// The constitutive interface: a pure rate law T̊ = T̊(T, e, q, D) for a material
// point in full 3D (MFEM HyperelasticModel style: the state goes in, the rate
// and, where asked, the tangent come out; nothing is hidden in the model).
//
// Inside this interface stresses and stretchings are tension positive
// (continuum convention, SPEC §6); stresses in kPa, stretching in 1/s.
// The void ratio always follows ė = (1 + e) tr D.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "common/enum_names.h"
#include "constitutive/eigen.h"
#include "constitutive/voigt.h"

namespace granasym {

enum class ModelKind { kHypoplasticClay, kModifiedCamClay, kHypoplasticSand };
template <>
struct EnumNames<ModelKind> {
  static constexpr EnumEntry<ModelKind> kEntries[] = {
      {ModelKind::kHypoplasticClay, "hypoplastic_clay", "Masin (2005) hypoplastic model for clays"},
      {ModelKind::kModifiedCamClay, "modified_cam_clay", "Modified Cam clay (Roscoe & Burland)"},
      {ModelKind::kHypoplasticSand, "hypoplastic_sand",
       "von Wolffersdorff (1996) hypoplastic model for sands"},
  };
};

// A rate law's branch decided by the state itself (ModelState::branch).
inline constexpr int kAutoBranch = -1;

// The state of a material point. `stress` is tension positive in kPa.
struct ModelState {
  Vector6 stress = Vector6::Zero();
  double void_ratio = 0.0;
  Eigen::VectorXd internal;  // model specific, see ConstitutiveModel::internal_names()
  // For a rate law with switches (ConstitutiveModel::num_switches), the
  // branch the element-test driver holds over a piece of integration (Cam
  // clay: elastic or plastic); kAutoBranch: the model decides from the state.
  int branch = kAutoBranch;
};

// Rates of the state for one stretching.
struct ModelRate {
  Vector6 stress_rate = Vector6::Zero();  // kPa/s, objective (no spin here)
  double void_ratio_rate = 0.0;           // 1/s
  Eigen::VectorXd internal_rate;
};

// Derivatives of y_dot = [stress_rate; internal_rate] (6 + n rows) with respect
// to the state x = [stress; ln(1+e); internal] (7 + n columns) and to D (6 columns).
struct RateJacobian {
  Eigen::MatrixXd d_state;
  Eigen::MatrixXd d_stretching;
};

class ConstitutiveModel {
 public:
  virtual ~ConstitutiveModel() = default;

  virtual ModelKind kind() const = 0;
  virtual int num_internal() const { return 0; }
  // Names (and units in brackets) of the internal variables, for output.
  virtual std::vector<std::string> internal_names() const { return {}; }

  // Stress (and internal) rate for the stretching D. When `tangent` is not null
  // it receives ∂T̊/∂D (6x6). Returns false, with the reason in `why`, when the
  // state lies outside the model's domain (then the outputs are unspecified).
  virtual bool Rate(const ModelState& state, const Vector6& stretching, ModelRate* rate,
                    Matrix6* tangent, std::string* why) const = 0;

  // Exact derivatives of the rates (automatic differentiation of the same code).
  virtual bool Jacobian(const ModelState& state, const Vector6& stretching, RateJacobian* jacobian,
                        std::string* why) const = 0;

  // Whether the model is defined at this state (compressive stress, ...).
  virtual bool IsAdmissible(const ModelState& state, std::string* why) const = 0;
  // Whether a test may start at this state: admissible, and inside the
  // model's state boundary surface where it has one (clay: OCR >= 1; sand:
  // e_d <= e <= e_i). A run may drift slightly outside it, never start there.
  virtual bool IsAdmissibleStart(const ModelState& state, std::string* why) const {
    return IsAdmissible(state, why);
  }

  // Hvorslev equivalent pressure p_e* (kPa): mean stress on the isotropic NCL at e.
  virtual double EquivalentPressure(double void_ratio) const = 0;
  // Void ratio at which p_e*/p = ocr for mean stress p (kPa).
  virtual double VoidRatioForOcr(double mean_stress, double ocr) const = 0;
  // A complete state for a stress (tension positive) and void ratio; fills the
  // internal variables consistently (Cam clay: p_c from the elastic line).
  virtual ModelState MakeState(const Vector6& stress, double void_ratio) const = 0;

  // Homogeneity in pressure: maps `state` to the state with stress (and
  // stress-like internal variables) times `factor` and p_e* times `factor`,
  // which evolves identically up to that scale (rate independence, barotropy
  // ∝ p). Returns false for models without this property. Used to keep long
  // asymptote searches within floating-point range.
  virtual bool ScaleState(double factor, ModelState* state) const { return false; }

  // Necessary sign conditions of the state, coded as in OdeSystem::Constraints
  // (tension-positive stress components; internal variables), which the
  // integrators enforce on every accepted step. Default: none.
  virtual void SignConstraints(Vector6* stress_codes, Eigen::VectorXd* internal_codes) const {
    stress_codes->setZero();
    internal_codes->setZero(num_internal());
  }

  // A rate law that is smooth on each of several branches (Cam clay: elastic
  // and plastic) and switches between them. The element-test driver holds
  // one branch over each piece of integration (ModelState::branch), the one
  // Branch gives at the piece's start, and ends the piece where a switch
  // function of that branch, positive while it holds, crosses zero; the next
  // piece starts there on the branch the state then takes. So no step mixes
  // two branches, which its error estimate cannot see. Default: none.
  virtual int num_switches() const { return 0; }
  virtual int Branch(const ModelState& state, const Vector6& stretching) const {
    return kAutoBranch;
  }
  virtual void Switches(const ModelState& state, const Vector6& stretching, double* values) const {}

  // The asymptotic state (paper Sec. 2, SPEC §7) of the stress direction ψ_σ
  // (rad, compression positive), where the model has it in closed form:
  // the direction ψ_ε (rad) of the stretching that leads to it and ln OCR.
  // False, with the reason, where the model has none (the default) or ψ_σ is
  // outside its domain.
  virtual bool AsymptoteOfStressDirection(double psi_sigma, double* psi_epsilon, double* ln_ocr,
                                          std::string* why) const;

  // Critical friction angle φ_c (rad) of the model, for the critical-state ratio.
  virtual double critical_friction_angle() const = 0;
  // One line with the parameters, for logs and HDF5 attributes.
  virtual std::string Describe() const = 0;
};

// OCR = p_e*/p (paper Eq. 2) of a state.
double OverconsolidationRatio(const ConstitutiveModel& model, const ModelState& state);

}  // namespace granasym
