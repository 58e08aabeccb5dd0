// The least-squares problem of a calibration: datasets of asymptotic states,
// the model and its free parameters, and the residuals (SPEC §7):
//
//   point with known ψ_ε (NCL, CSL, compression, extension):
//     Δψ_σ = ψ_σ,model(ψ_ε) − ψ_σ           (deg)  / σ_ψ (deg)   · √weight
//     Δln(1+e) = N − λ* ln(p OCR(ψ_ε)/p_r) − ln(1+e)  / σ_v     · √weight
//   ASBS point (known ψ_σ, not ψ_ε):
//     Δln(1+e) with OCR(ψ_σ) of the state boundary surface  / σ_v · √weight
//
// The weighted residuals are dimensionless; the raw ones keep their units in
// the report. Unloading points and points of weight 0 do not enter the
// objective (they are evaluated and drawn). The sand model (not homogeneous
// in p) is compared at each state's own p (AsymptotePredictor::PredictAtPressures):
// Δψ_σ as above, Δln(1+e) = ln(1+e_model(p)) − ln(1+e).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "calibration/asymptote_predictor.h"
#include "calibration/model_parameters.h"
#include "calibration/state_dataset.h"

namespace granasym::calibration {

struct PointResidual {
  int dataset = 0;
  int point = 0;
  double psi_sigma_model = 0.0;         // rad
  double ln_volume_model = 0.0;         // ln(1+e) of the model at the point's p
  double ln_ocr_model = 0.0;            // ln(p_e*/p) of the model's asymptote
  double psi_sigma_residual_deg = 0.0;  // model − data (deg); NaN when not a residual
  double ln_volume_residual = 0.0;      // model − data; NaN for unloading points
  bool clamped = false;                 // ψ_ε outside the model's asymptote range
};

// The free parameters that these data cannot identify whatever the fit
// (structurally, by FittedParameter::identified_by of the model's traits:
// e.g. lambda* without states at two mean stresses, r or ν without
// non-isotropic states in two directions besides the critical state), each
// with what data it needs, by requirement (Identification order) and then in
// parameter order. The sand's parameters are judged from the Jacobian
// instead (RunCalibration, calibration_report.h), so none is listed for it.
std::vector<std::pair<int, std::string>> Unidentifiable(const std::vector<StateDataset>& datasets,
                                                        const ModelParameters& parameters);

class CalibrationProblem {
 public:
  // Throws InputError for empty datasets, no asymptotic states, fewer
  // residuals than free parameters, or data that cannot identify a free
  // parameter (each message names the parameter and what data it needs).
  CalibrationProblem(std::vector<StateDataset> datasets, ModelParameters parameters,
                     const PredictorOptions& predictor_options);

  const std::vector<StateDataset>& datasets() const { return datasets_; }
  const ModelParameters& parameters() const { return parameters_; }
  const AsymptotePredictor& predictor() const { return predictor_; }
  int num_residuals() const { return num_residuals_; }
  int num_free() const { return static_cast<int>(free_.size()); }
  const std::vector<int>& free_indices() const { return free_; }
  // Free-parameter bounds and starting values, in free order.
  std::vector<double> FreeLower() const;
  std::vector<double> FreeUpper() const;
  std::vector<double> FreeStart() const;

  // Weighted residuals (num_residuals) for the free values; false with the
  // reason for parameters outside the model's domain.
  bool Residuals(const double* free_values, double* residuals, std::string* why) const;
  // ½ Σ r²; +∞ for invalid parameters. Counts evaluations.
  double Cost(const std::vector<double>& free_values) const;
  // Raw residuals per point (all points, unloading included) at full values.
  bool Evaluate(const std::vector<double>& values, std::vector<PointResidual>* residuals,
                std::string* why) const;
  // Labels of the weighted residuals: "dataset/source: psi_sigma" etc.
  std::vector<std::string> ResidualLabels() const;
  // The (dataset, point) of each weighted residual, in the order of Residuals.
  std::vector<std::pair<int, int>> ResidualPoints() const;

  long evaluations() const { return evaluations_; }

 private:
  // A model without a linear NCL (the sand): each state at its own p.
  bool EvaluateAtOwnPressures(const std::vector<double>& values,
                              std::vector<PointResidual>* residuals, std::string* why) const;

  std::vector<StateDataset> datasets_;
  ModelParameters parameters_;
  AsymptotePredictor predictor_;
  std::vector<int> free_;
  // Distinct ψ_ε values and, per point, the index into them (−1: none) and
  // into the ASBS ψ_σ list (−1: none).
  std::vector<double> psi_epsilons_;
  std::vector<double> asbs_psi_sigmas_;
  std::vector<std::vector<int>> stretching_index_;
  std::vector<std::vector<int>> stress_index_;
  int num_residuals_ = 0;
  mutable long evaluations_ = 0;
};

}  // namespace granasym::calibration
