// Residuals of asymptotic states and the identifiability checks.
#include "calibration/calibration_problem.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <memory>
#include <set>

#include "common/error.h"
#include "common/state_measures.h"

namespace granasym::calibration {

CalibrationProblem::CalibrationProblem(std::vector<StateDataset> datasets,
                                       ModelParameters parameters,
                                       const PredictorOptions& predictor_options,
                                       std::vector<PathDataset> paths)
    : datasets_(std::move(datasets)),
      paths_(std::move(paths)),
      parameters_(std::move(parameters)),
      predictor_(parameters_.kind(), predictor_options),
      free_(parameters_.FreeIndices()) {
  if (datasets_.empty()) throw InputError("calibration: no datasets");
  parameters_.Validate();
  stretching_index_.resize(datasets_.size());
  stress_index_.resize(datasets_.size());
  for (size_t d = 0; d < datasets_.size(); ++d) {
    datasets_[d].Validate();
    for (const AsymptoticStatePoint& point : datasets_[d].points) {
      int s = -1, a = -1;
      if (point.kind == StateKind::kAsbs && !parameters_.traits().linear_ncl) {
        throw InputError(fmt::format(
            "dataset '{}': {}: ASBS cross-section points need a model with an analytic ASBS "
            "({}), not {}",
            datasets_[d].name, point.source,
            ModelNamesWhere([](const ModelTraits& t) { return t.linear_ncl; }),
            ToString(parameters_.kind())));
      }
      if (point.HasStretching()) {
        for (size_t k = 0; k < psi_epsilons_.size(); ++k) {
          if (psi_epsilons_[k] == point.psi_epsilon) s = static_cast<int>(k);
        }
        if (s < 0) {
          s = static_cast<int>(psi_epsilons_.size());
          psi_epsilons_.push_back(point.psi_epsilon);
        }
        if (point.IsFitted()) num_residuals_ += 2;
      } else if (point.kind == StateKind::kAsbs) {
        if (predictor_options.method == AsymptoteMethod::kIntegrated) {
          throw InputError(
              fmt::format("dataset '{}': {}: ASBS points need analytic asymptotes (asymptotes = "
                          "\"integrated\" follows stretching directions only)",
                          datasets_[d].name, point.source));
        }
        a = static_cast<int>(asbs_psi_sigmas_.size());
        asbs_psi_sigmas_.push_back(point.psi_sigma);
        if (point.IsFitted()) num_residuals_ += 1;
      }
      stretching_index_[d].push_back(s);
      stress_index_[d].push_back(a);
    }
  }
  if (num_residuals_ == 0) {
    throw InputError(
        "calibration: the datasets hold no fitted asymptotic states (only unloading points or "
        "datasets with weight = 0); path datasets and unloading branches need asymptotic "
        "states beside them");
  }
  num_state_residuals_ = num_residuals_;
  for (const StateDataset& dataset : datasets_) {
    for (const AsymptoticStatePoint& point : dataset.points) {
      num_residuals_ += point.IsFittedUnloading() ? 1 : 0;
    }
  }
  for (const PathDataset& path : paths_) {
    path.Validate();
    num_residuals_ += path.NumResiduals();
  }
  if (num_residuals_ <= num_free()) {
    throw InputError(fmt::format(
        "calibration: too few data: {} residuals for {} free parameters (need more residuals "
        "than free parameters; fix parameters or add states)",
        num_residuals_, num_free()));
  }
  const std::vector<std::pair<int, std::string>> unidentified =
      Unidentifiable(datasets_, parameters_, paths_);
  if (!unidentified.empty()) {
    throw InputError(fmt::format(
        "calibration: parameter {} cannot be identified by these data: {} (fix it with "
        "free = false and a value, or add states)",
        parameters_.specs()[unidentified.front().first].name, unidentified.front().second));
  }
}

namespace {

// What the fitted asymptotic states of `datasets` hold, for identifiability.
struct StateCoverage {
  std::set<double> ln_p_with_line;            // distinct p among points on asymptotic lines
  int non_isotropic = 0;                      // points with ψ_ε ≠ 0 or ASBS points
  std::set<double> non_isotropic_directions;  // besides the critical state

  StateCoverage(const std::vector<StateDataset>& datasets, const std::vector<PathDataset>& paths) {
    for (size_t k = 0; k < paths.size(); ++k) {
      const PathDataset& path = paths[k];
      if (path.NumResiduals() == 0) continue;
      double lo = path.samples.front().PsiSigma(), hi = lo;
      for (const PathSample& s : path.samples) {
        lo = std::min(lo, s.PsiSigma());
        hi = std::max(hi, s.PsiSigma());
        ln_p_with_line.insert(std::round(std::log(s.MeanStress()) * 1e6));
      }
      // A path with shear passes through many stress directions.
      if (hi - lo > 1.0 * kDegree) {
        ++non_isotropic;
        non_isotropic_directions.insert(100.0 + lo + 0.1 * k);
        non_isotropic_directions.insert(100.0 + hi + 0.1 * k);
      }
    }
    for (const StateDataset& dataset : datasets) {
      for (const AsymptoticStatePoint& point : dataset.points) {
        if (!point.IsFitted()) continue;
        ln_p_with_line.insert(std::round(std::log(point.mean_stress) * 1e6));
        if (point.kind != StateKind::kNcl) {
          ++non_isotropic;
          if (point.kind == StateKind::kCsl) continue;  // OCR_c and ψ_σ(c) need φ_c only
          non_isotropic_directions.insert(point.kind == StateKind::kAsbs ? point.psi_sigma + 10.0
                                                                         : point.psi_epsilon);
        }
      }
    }
  }

  // Whether these states can identify a parameter determined by `by`
  // (kJacobian: judged from the fit instead, see calibration_report.h).
  bool Identifies(Identification by) const {
    switch (by) {
      case Identification::kTwoMeanStresses:
        return ln_p_with_line.size() >= 2;
      case Identification::kOffIsotropicAxis:
        return non_isotropic > 0;
      case Identification::kTwoOffAxisDirections:
        return non_isotropic_directions.size() >= 2;
      case Identification::kAnyState:
      case Identification::kJacobian:
        return true;
    }
    return true;
  }
};

}  // namespace

std::vector<std::pair<int, std::string>> Unidentifiable(const std::vector<StateDataset>& datasets,
                                                        const ModelParameters& parameters,
                                                        const std::vector<PathDataset>& paths) {
  std::vector<std::pair<int, std::string>> found;
  const StateCoverage coverage(datasets, paths);
  const std::vector<FittedParameter>& fitted = parameters.traits().parameters;
  // By requirement first (the most basic data first), then in parameter order.
  for (Identification by : EnumValues<Identification>()) {
    for (size_t i = 0; i < fitted.size(); ++i) {
      if (fitted[i].identified_by != by || !parameters.specs()[i].free) continue;
      if (!coverage.Identifies(by)) {
        found.emplace_back(static_cast<int>(i),
                           fmt::format("{} needs {}", fitted[i].traits.key, EnumDescription(by)));
      }
    }
  }
  return found;
}

std::vector<double> CalibrationProblem::FreeLower() const {
  std::vector<double> v;
  for (int i : free_) v.push_back(parameters_.specs()[i].lower);
  return v;
}
std::vector<double> CalibrationProblem::FreeUpper() const {
  std::vector<double> v;
  for (int i : free_) v.push_back(parameters_.specs()[i].upper);
  return v;
}
std::vector<double> CalibrationProblem::FreeStart() const {
  std::vector<double> v;
  for (int i : free_) v.push_back(parameters_.specs()[i].value);
  return v;
}

bool CalibrationProblem::Evaluate(const std::vector<double>& values,
                                  std::vector<PointResidual>* residuals, std::string* why) const {
  if (!parameters_.traits().linear_ncl) return EvaluateAtOwnPressures(values, residuals, why);
  std::vector<Prediction> by_stretching, by_stress;
  if (!predictor_.Predict(values, psi_epsilons_, asbs_psi_sigmas_, &by_stretching, &by_stress,
                          why)) {
    return false;
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double n = values[kNIntercept], lambda = values[kLambdaStar];
  residuals->clear();
  for (size_t d = 0; d < datasets_.size(); ++d) {
    const StateDataset& dataset = datasets_[d];
    for (size_t k = 0; k < dataset.points.size(); ++k) {
      const AsymptoticStatePoint& point = dataset.points[k];
      PointResidual r;
      r.dataset = static_cast<int>(d);
      r.point = static_cast<int>(k);
      const int s = stretching_index_[d][k], a = stress_index_[d][k];
      const Prediction* prediction = s >= 0 ? &by_stretching[s] : a >= 0 ? &by_stress[a] : nullptr;
      // Unloading points: compare with the NCL itself (for the report only).
      r.psi_sigma_model = prediction ? prediction->psi_sigma : nan;
      r.ln_ocr_model = prediction ? prediction->ln_ocr : nan;
      r.clamped = prediction && prediction->clamped;
      r.ln_volume_model = prediction ? n - lambda * (std::log(point.mean_stress) + r.ln_ocr_model)
                                     : n - lambda * std::log(point.mean_stress);
      r.psi_sigma_residual_deg = s >= 0 ? (r.psi_sigma_model - point.psi_sigma) / kDegree : nan;
      r.ln_volume_residual = prediction ? r.ln_volume_model - std::log1p(point.void_ratio) : nan;
      if (!std::isfinite(r.ln_volume_model) || (s >= 0 && !std::isfinite(r.psi_sigma_model))) {
        *why = fmt::format("non-finite prediction at {}", point.source);
        return false;
      }
      residuals->push_back(r);
    }
  }
  return EvaluateUnloading(values, residuals, why);
}

bool CalibrationProblem::EvaluateUnloading(const std::vector<double>& values,
                                           std::vector<PointResidual>* residuals,
                                           std::string* why) const {
  std::unique_ptr<ConstitutiveModel> model;
  size_t j = 0;
  for (size_t d = 0; d < datasets_.size(); ++d) {
    const std::vector<AsymptoticStatePoint>& points = datasets_[d].points;
    for (size_t k = 0; k < points.size(); ++j) {
      const AsymptoticStatePoint& first = points[k];
      if (!(first.kind == StateKind::kUnloading && first.branch_start_p > 0 &&
            first.branch_start_e > 0)) {
        ++k;
        continue;
      }
      // The consecutive points of one branch (same start), in file order.
      std::vector<double> targets;
      size_t end = k;
      while (end < points.size() && points[end].kind == StateKind::kUnloading &&
             points[end].branch_start_p == first.branch_start_p &&
             points[end].branch_start_e == first.branch_start_e) {
        targets.push_back(points[end].mean_stress);
        ++end;
      }
      if (!model) {
        model = MakeModel(parameters_.kind(), values, why);
        if (!model) return false;
      }
      std::vector<double> ln_volume;
      if (!PredictIsotropicBranch(*model, first.branch_start_p, first.branch_start_e, targets,
                                  &ln_volume, why)) {
        *why = fmt::format("{}: {}", first.source, *why);
        return false;
      }
      for (size_t m = 0; m < targets.size(); ++m) {
        PointResidual& r = (*residuals)[j + m];
        r.ln_volume_model = ln_volume[m];
        r.ln_volume_residual = ln_volume[m] - std::log1p(points[k + m].void_ratio);
      }
      j += targets.size() - 1;
      k = end;
    }
  }
  return true;
}

bool CalibrationProblem::EvaluatePaths(const std::vector<double>& values,
                                       std::vector<PathPrediction>* predictions,
                                       std::string* why) const {
  predictions->assign(paths_.size(), PathPrediction());
  if (paths_.empty()) return true;
  const std::unique_ptr<ConstitutiveModel> model = MakeModel(parameters_.kind(), values, why);
  if (!model) return false;
  for (size_t k = 0; k < paths_.size(); ++k) {
    if (!PredictPath(*model, paths_[k], &(*predictions)[k], why)) return false;
  }
  return true;
}

ResidualRange CalibrationProblem::Group(ResidualGroup group) const {
  if (group == ResidualGroup::kAsymptotic) return {0, num_state_residuals_};
  return {num_state_residuals_, num_residuals_ - num_state_residuals_};
}

void CalibrationProblem::SetGroupWeights(double asymptotic, double path) {
  GRANASYM_CHECK(asymptotic >= 0 && path >= 0 && std::isfinite(asymptotic) && std::isfinite(path))
      << "group weights " << asymptotic << ", " << path << " must be finite and >= 0";
  group_weight_[0] = asymptotic;
  group_weight_[1] = path;
}

CalibrationProblem CalibrationProblem::WithParameters(ModelParameters parameters) const {
  CalibrationProblem problem(datasets_, std::move(parameters), predictor_.options(), paths_);
  problem.SetGroupWeights(group_weight_[0], group_weight_[1]);
  return problem;
}

bool CalibrationProblem::EvaluateAtOwnPressures(const std::vector<double>& values,
                                                std::vector<PointResidual>* residuals,
                                                std::string* why) const {
  // Every point at its own p: states along its ψ_ε, unloading points on e_i.
  std::vector<double> psi_epsilons, mean_stresses;
  for (const StateDataset& dataset : datasets_) {
    for (const AsymptoticStatePoint& point : dataset.points) {
      psi_epsilons.push_back(point.HasStretching() ? point.psi_epsilon : 0.0);
      mean_stresses.push_back(point.mean_stress);
    }
  }
  std::vector<StatePrediction> states;
  if (!predictor_.PredictAtPressures(values, psi_epsilons, mean_stresses, &states, why)) {
    return false;
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  residuals->clear();
  size_t j = 0;
  for (size_t d = 0; d < datasets_.size(); ++d) {
    const StateDataset& dataset = datasets_[d];
    for (size_t k = 0; k < dataset.points.size(); ++k, ++j) {
      const AsymptoticStatePoint& point = dataset.points[k];
      PointResidual r;
      r.dataset = static_cast<int>(d);
      r.point = static_cast<int>(k);
      r.psi_sigma_model = point.HasStretching() ? states[j].psi_sigma : nan;
      r.ln_volume_model = states[j].ln_volume;
      r.ln_ocr_model = point.HasStretching() ? states[j].ln_ocr : nan;
      r.psi_sigma_residual_deg =
          point.HasStretching() ? (r.psi_sigma_model - point.psi_sigma) / kDegree : nan;
      r.ln_volume_residual =
          point.IsAsymptotic() ? r.ln_volume_model - std::log1p(point.void_ratio) : nan;
      if (!std::isfinite(r.ln_volume_model) ||
          (point.HasStretching() && !std::isfinite(r.psi_sigma_model))) {
        *why = fmt::format("non-finite prediction at {}", point.source);
        return false;
      }
      residuals->push_back(r);
    }
  }
  return EvaluateUnloading(values, residuals, why);
}

bool CalibrationProblem::Residuals(const double* free_values, double* residuals,
                                   std::string* why) const {
  ++evaluations_;
  const std::vector<double> values =
      parameters_.WithFree(std::vector<double>(free_values, free_values + free_.size()));
  std::vector<PointResidual> raw;
  if (!Evaluate(values, &raw, why)) return false;
  int j = 0;
  const double state_scale = std::sqrt(group_weight_[0]);
  const double path_scale = std::sqrt(group_weight_[1]);
  for (const PointResidual& r : raw) {
    const AsymptoticStatePoint& point = datasets_[r.dataset].points[r.point];
    if (!point.IsFitted()) continue;
    const double w = state_scale * std::sqrt(point.weight);
    if (point.HasStretching()) {
      residuals[j++] = w * r.psi_sigma_residual_deg * kDegree / point.psi_sigma_uncertainty;
    }
    residuals[j++] = w * r.ln_volume_residual / point.ln_volume_uncertainty;
  }
  GRANASYM_CHECK(j == num_state_residuals_) << j << " vs " << num_state_residuals_;
  for (const PointResidual& r : raw) {
    const AsymptoticStatePoint& point = datasets_[r.dataset].points[r.point];
    if (!point.IsFittedUnloading()) continue;
    residuals[j++] =
        path_scale * std::sqrt(point.weight) * r.ln_volume_residual / point.ln_volume_uncertainty;
  }
  if (!paths_.empty()) {
    std::vector<PathPrediction> predictions;
    if (!EvaluatePaths(values, &predictions, why)) return false;
    for (size_t k = 0; k < paths_.size(); ++k) {
      const PathDataset& path = paths_[k];
      if (path.NumResiduals() == 0) continue;
      const PathPrediction& m = predictions[k];
      const double w =
          path_scale * std::sqrt(path.weight / static_cast<double>(path.samples.size() - 1));
      for (size_t i = 1; i < path.samples.size(); ++i) {
        const PathSample& s = path.samples[i];
        residuals[j++] =
            w * (std::log(m.mean_stress[i]) - std::log(s.MeanStress())) / path.ln_p_uncertainty;
        residuals[j++] = w * (m.psi_sigma[i] - s.PsiSigma()) / path.psi_sigma_uncertainty;
        if (path.control == PathControl::kDrained) {
          residuals[j++] = w * (std::log1p(m.void_ratio[i]) - std::log1p(s.void_ratio)) /
                           path.ln_volume_uncertainty;
        }
      }
    }
  }
  GRANASYM_CHECK(j == num_residuals_) << j << " vs " << num_residuals_;
  for (int i = 0; i < j; ++i) {
    if (!std::isfinite(residuals[i])) {
      *why = fmt::format("non-finite residual {} of {}", i, j);
      return false;
    }
  }
  return true;
}

double CalibrationProblem::Cost(const std::vector<double>& free_values) const {
  std::vector<double> r(static_cast<size_t>(num_residuals_));
  std::string why;
  if (!Residuals(free_values.data(), r.data(), &why)) {
    return std::numeric_limits<double>::infinity();
  }
  double cost = 0;
  for (double x : r) cost += 0.5 * x * x;
  return std::isfinite(cost) ? cost : std::numeric_limits<double>::infinity();
}

std::vector<std::string> CalibrationProblem::ResidualLabels() const {
  std::vector<std::string> labels;
  for (const StateDataset& dataset : datasets_) {
    for (const AsymptoticStatePoint& point : dataset.points) {
      if (!point.IsFitted()) continue;
      if (point.HasStretching())
        labels.push_back(dataset.name + ": " + point.source + ": psi_sigma");
      labels.push_back(dataset.name + ": " + point.source + ": ln_1_plus_e");
    }
  }
  for (const StateDataset& dataset : datasets_) {
    for (const AsymptoticStatePoint& point : dataset.points) {
      if (point.IsFittedUnloading())
        labels.push_back(dataset.name + ": " + point.source + ": unloading ln_1_plus_e");
    }
  }
  for (const PathDataset& path : paths_) {
    if (path.NumResiduals() == 0) continue;
    for (size_t i = 1; i < path.samples.size(); ++i) {
      const std::string at = fmt::format("{}: sample {}: ", path.name, i);
      labels.push_back(at + "ln_p");
      labels.push_back(at + "psi_sigma");
      if (path.control == PathControl::kDrained) labels.push_back(at + "ln_1_plus_e");
    }
  }
  return labels;
}

std::vector<std::pair<int, int>> CalibrationProblem::ResidualPoints() const {
  std::vector<std::pair<int, int>> owners;
  for (size_t d = 0; d < datasets_.size(); ++d) {
    for (size_t k = 0; k < datasets_[d].points.size(); ++k) {
      const AsymptoticStatePoint& point = datasets_[d].points[k];
      if (!point.IsFitted()) continue;
      const std::pair<int, int> owner(static_cast<int>(d), static_cast<int>(k));
      if (point.HasStretching()) owners.push_back(owner);
      owners.push_back(owner);
    }
  }
  return owners;
}

}  // namespace granasym::calibration
