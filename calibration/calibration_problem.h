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
//
// Beyond the asymptotic states (issue 36 §3), two kinds of residuals of
// whole paths, integrated with the model:
//   unloading point with weight > 0 and a branch start (IsFittedUnloading):
//     Δln(1+e) of the model started at the branch's (p, e) and driven
//     isotropically to the point's p  / σ_v · √weight
//   path dataset (path_dataset.h): per sample, ln p, ψ_σ (and ln(1+e) under
//     drained control) of the model along the DEM's strain path.
// The residual vector is grouped (ResidualGroup): the asymptotic states
// first, then the path residuals (unloading points, then paths), so that a
// trade-off study (Pareto front) can weight the two groups (SetGroupWeights).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "calibration/asymptote_predictor.h"
#include "calibration/model_parameters.h"
#include "calibration/path_dataset.h"
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
                                        // without a branch start
  bool clamped = false;                 // ψ_ε outside the model's asymptote range
};

// The two groups of residuals (issue 36 §3, multi-objective): asymptotic
// states, and whole paths (unloading branches and path datasets).
enum class ResidualGroup { kAsymptotic, kPath };
struct ResidualRange {
  int begin = 0, count = 0;  // into the weighted residual vector
};

// The free parameters that these data cannot identify whatever the fit
// (structurally, by FittedParameter::identified_by of the model's traits:
// e.g. lambda* without states at two mean stresses, r or ν without
// non-isotropic states in two directions besides the critical state), each
// with what data it needs, by requirement (Identification order) and then in
// parameter order. The sand's parameters are judged from the Jacobian
// instead (RunCalibration, calibration_report.h), so none is listed for it.
// Fitted path datasets and unloading branches count as states off the
// isotropic axis (a path with shear: two directions) and at the mean
// stresses they span.
std::vector<std::pair<int, std::string>> Unidentifiable(const std::vector<StateDataset>& datasets,
                                                        const ModelParameters& parameters,
                                                        const std::vector<PathDataset>& paths = {});

class CalibrationProblem {
 public:
  // Throws InputError for empty datasets, no asymptotic states, fewer
  // residuals than free parameters, or data that cannot identify a free
  // parameter (each message names the parameter and what data it needs).
  CalibrationProblem(std::vector<StateDataset> datasets, ModelParameters parameters,
                     const PredictorOptions& predictor_options,
                     std::vector<PathDataset> paths = {});

  const std::vector<StateDataset>& datasets() const { return datasets_; }
  const std::vector<PathDataset>& paths() const { return paths_; }
  // Where each group lies in the weighted residual vector.
  ResidualRange Group(ResidualGroup group) const;
  // Multiplies the squared residuals of each group (default 1, 1; each ≥ 0).
  void SetGroupWeights(double asymptotic, double path);
  double group_weight(ResidualGroup group) const {
    return group_weight_[group == ResidualGroup::kAsymptotic ? 0 : 1];
  }
  // The same data (datasets, paths, predictor options, group weights) with
  // other parameters: which are free, their values and bounds (profile
  // refits, the Pareto sweep's weighted fits).
  CalibrationProblem WithParameters(ModelParameters parameters) const;
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
  // The model along every path dataset at full values; false with the
  // reason when the parameters make no model or a path cannot start.
  bool EvaluatePaths(const std::vector<double>& values, std::vector<PathPrediction>* predictions,
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

  // ln(1+e) of the model at the unloading points with a branch start (NaN
  // elsewhere), by dataset and point.
  bool EvaluateUnloading(const std::vector<double>& values, std::vector<PointResidual>* residuals,
                         std::string* why) const;

  std::vector<StateDataset> datasets_;
  std::vector<PathDataset> paths_;
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
  int num_state_residuals_ = 0;  // the asymptotic group; the path group follows
  double group_weight_[2] = {1.0, 1.0};
  mutable long evaluations_ = 0;
};

}  // namespace granasym::calibration
