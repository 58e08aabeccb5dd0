// What a model predicts for asymptotic states (SPEC §7): for a stretching
// direction ψ_ε the asymptotic stress direction ψ_σ and ln OCR, i.e. the line
// ln(1+e) = N − λ* ln(p OCR/p_r) parallel to the NCL; for a stress direction
// ψ_σ (ASBS cross-sections) the OCR of the state boundary surface.
//
// Analytic (default), for the models with a linear NCL (ModelTraits::linear_ncl):
//   the model's closed form ψ_σ → (ψ_ε, OCR)
//   (ConstitutiveModel::AsymptoteOfStressDirection: the ASBS of Mašín & Herle
//   (2005) for the hypoplastic clay, the Roscoe surface for Modified Cam
//   clay), inverted for ψ_ε on a ψ_σ grid refined by the Illinois method.
// Hypoplastic sand (not homogeneous in p, no analytic ASBS; SPEC §7): the
// state at the DEM state's own p, along proportional stretching at its ψ_ε
// from an isotropic state on the limit line e_i far from it (a tenth of the
// lowest p of that ψ_ε for compression, ten times the highest for
// extension), interpolated in ln p; closed forms on the axes: e_i(p) at
// ψ_ε = 0 and the critical state e_c(p), ψ_σ(φ_c) at ψ_ε = 90°.
// Integrated: proportional stretching from an isotropic normally consolidated
// state until stationary (IntegrateAsymptote), for each distinct ψ_ε (slow;
// the reference for the analytic forms).
#pragma once

#include <string>
#include <vector>

#include "common/enum_names.h"
#include "constitutive/asymptotic_states.h"
#include "constitutive/constitutive_model.h"

namespace granasym::calibration {

enum class AsymptoteMethod { kAnalytic, kIntegrated };

}  // namespace granasym::calibration

namespace granasym {
template <>
struct EnumNames<calibration::AsymptoteMethod> {
  using M = calibration::AsymptoteMethod;
  static constexpr EnumEntry<M> kEntries[] = {
      {M::kAnalytic, "analytic", "closed-form asymptotic states (default)"},
      {M::kIntegrated, "integrated", "proportional stretching until stationary (slow reference)"},
  };
};
}  // namespace granasym

namespace granasym::calibration {

// The name-table functions (common/enum_names.h) for this namespace's enums.
using granasym::FromString;
using granasym::ToString;

struct PredictorOptions {
  AsymptoteMethod method = AsymptoteMethod::kAnalytic;
  // Analytic: ψ_σ grid over the admissible range used to bracket each ψ_ε;
  // 120 points resolve the steep ends of the hypoplastic curve.
  int curve_points = 120;
  // Analytic: the inversion stops when the ψ_σ bracket is below this (rad).
  double psi_sigma_tolerance = 1e-12;
  // Integrated: the search settings and the isotropic start (kPa).
  AsymptoteSearchOptions search;
  double initial_mean_stress = 100.0;
  // Sand: the element tests along the DEM's paths (ERK 5; 1e-9 keeps the
  // central differences of the fit clean).
  ElementTestOptions sand_paths = SandPathOptions();

  static ElementTestOptions SandPathOptions() {
    ElementTestOptions options;
    options.integrator.relative_tolerance = options.integrator.absolute_tolerance = 1e-9;
    return options;
  }
  bool IsValid(std::string* why) const;
};

struct Prediction {
  double psi_epsilon = 0.0;  // rad
  double psi_sigma = 0.0;    // rad
  double ln_ocr = 0.0;       // ln(p_e*/p)
  // The requested ψ_ε lies outside the model's asymptote range: the state of
  // the nearest end is returned (residuals stay continuous and large).
  bool clamped = false;
};

// A state the model reaches at a given mean stress (sand model).
struct StatePrediction {
  double psi_sigma = 0.0;  // rad
  double ln_volume = 0.0;  // ln(1+e) at the requested p
  double ln_ocr = 0.0;     // ln(p_e*/p) of the model (its own NCL e_i)
};

class AsymptotePredictor {
 public:
  // The options must be valid (GRANASYM_CHECK).
  AsymptotePredictor(ModelKind kind, const PredictorOptions& options);

  ModelKind kind() const { return kind_; }
  const PredictorOptions& options() const { return options_; }

  // Predictions for each ψ_ε in `psi_epsilons` and each ψ_σ in `psi_sigmas`
  // (rad) with the full parameter vector (model_parameters.h). Returns false,
  // with the reason, for invalid parameters or a failed evaluation.
  bool Predict(const std::vector<double>& parameters, const std::vector<double>& psi_epsilons,
               const std::vector<double>& psi_sigmas, std::vector<Prediction>* by_stretching,
               std::vector<Prediction>* by_stress, std::string* why) const;

  // Sand model: the state along proportional stretching at each ψ_ε
  // (rad) when p reaches the paired mean stress (kPa); see the file comment.
  bool PredictAtPressures(const std::vector<double>& parameters,
                          const std::vector<double>& psi_epsilons,
                          const std::vector<double>& mean_stresses,
                          std::vector<StatePrediction>* states, std::string* why) const;

  // The model's asymptotes for `points` stress directions evenly spaced over
  // the admissible ψ_σ range (analytic forms), for figures; false for the
  // sand model (no analytic ASBS).
  bool Curve(const std::vector<double>& parameters, int points, std::vector<Prediction>* curve,
             std::string* why) const;

 private:
  ModelKind kind_;
  PredictorOptions options_;
};

}  // namespace granasym::calibration
