// Analytic and integrated asymptotic states of the calibrated models.
#include "calibration/asymptote_predictor.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>

#include "calibration/model_parameters.h"
#include "common/error.h"
#include "common/root_finding.h"
#include "common/state_measures.h"
#include "constitutive/element_driver.h"
#include "constitutive/hypoplastic_sand.h"

namespace granasym::calibration {

bool PredictorOptions::IsValid(std::string* why) const {
  if (curve_points < 10) {
    *why = fmt::format("curve_points = {} must be >= 10", curve_points);
    return false;
  }
  if (!(psi_sigma_tolerance > 0 && psi_sigma_tolerance < 1e-3)) {
    *why = fmt::format("psi_sigma_tolerance = {} rad must be in (0, 1e-3)", psi_sigma_tolerance);
    return false;
  }
  if (!(initial_mean_stress > 0)) {
    *why = fmt::format("initial_mean_stress = {} kPa must be > 0", initial_mean_stress);
    return false;
  }
  return search.IsValid(why);
}

namespace {

// Admissible stress directions: σ_a → 0 and σ_r → 0, with a margin.
const double kLowestPsiSigma = -std::atan(1.0 / std::sqrt(2.0)) + 1e-6;
const double kHighestPsiSigma = std::atan(std::sqrt(2.0)) - 1e-6;

using StressMap = std::function<bool(double psi_sigma, Prediction*, std::string*)>;

// The model's closed-form asymptote of a stress direction as a Prediction.
bool AsymptoteOf(const ConstitutiveModel& model, double psi_sigma, Prediction* out,
                 std::string* why) {
  double psi_epsilon = 0.0, ln_ocr = 0.0;
  if (!model.AsymptoteOfStressDirection(psi_sigma, &psi_epsilon, &ln_ocr, why)) return false;
  out->psi_sigma = psi_sigma;
  out->psi_epsilon = psi_epsilon;
  out->ln_ocr = ln_ocr;
  out->clamped = false;
  return true;
}

// ψ_ε → state by bracketing on the grid and the Illinois method in ψ_σ.
bool Invert(const StressMap& map, const std::vector<Prediction>& grid, double target,
            double tolerance, Prediction* out, std::string* why) {
  if (target <= grid.front().psi_epsilon) {
    *out = grid.front();
    out->clamped = target < grid.front().psi_epsilon;
    return true;
  }
  for (size_t i = 1; i < grid.size(); ++i) {
    const Prediction& a = grid[i - 1];
    const Prediction& b = grid[i];
    if (!(a.psi_epsilon <= target && target <= b.psi_epsilon)) continue;
    const double g_a = a.psi_epsilon - target, g_b = b.psi_epsilon - target;
    Prediction best = std::abs(g_a) < std::abs(g_b) ? a : b;
    IllinoisOptions illinois;
    illinois.width_tolerance = tolerance;
    illinois.max_iterations = 100;
    illinois.formula = SecantFormula::kWeightedMean;
    illinois.test_initial_bracket = true;
    illinois.returned = ReturnedPoint::kLastPoint;
    auto g_at = [&](double x, double* g) {
      Prediction mid;
      if (!map(x, &mid, why)) return false;
      *g = mid.psi_epsilon - target;
      best = mid;
      return true;
    };
    if (IllinoisRoot(g_at, a.psi_sigma, g_a, b.psi_sigma, g_b, illinois).failed) return false;
    *out = best;
    out->psi_epsilon = target;
    return true;
  }
  *out = grid.back();
  out->clamped = true;
  return true;
}

// The sand's states along one proportional path, interpolated at `targets`.
bool SandPath(const HypoplasticSand& model, double psi_epsilon, const std::vector<double>& targets,
              const PredictorOptions& options, std::vector<StatePrediction>* out,
              std::string* why) {
  const double lo = *std::min_element(targets.begin(), targets.end());
  const double hi = *std::max_element(targets.begin(), targets.end());
  const double psi_c =
      std::atan(std::sqrt(2.0) / 3.0 * CriticalStateRatio(model.critical_friction_angle()));
  out->assign(targets.size(), StatePrediction());
  auto closed_form = [&](double e_of_p(const HypoplasticSand&, double), double psi) {
    for (size_t k = 0; k < targets.size(); ++k) {
      const double e = e_of_p(model, targets[k]);
      (*out)[k].psi_sigma = psi;
      (*out)[k].ln_volume = std::log1p(e);
      (*out)[k].ln_ocr = std::log(model.EquivalentPressure(e) / targets[k]);
    }
    return true;
  };
  if (std::abs(psi_epsilon) < 1e-9) {
    return closed_form(
        [](const HypoplasticSand& m, double p) { return m.LimitVoidRatiosAt(p).loosest; }, 0.0);
  }
  // Isochoric, and the drained triaxial states the readers count as critical
  // (within 2° of 90°, a ψ_ε measured from strain increments): the critical
  // state at the state's p (a proportional path at 89.5° from a loose start
  // runs to p = 0 instead).
  if (std::abs(psi_epsilon - 0.5 * kPi) < 2.0 * kDegree) {
    return closed_form(
        [](const HypoplasticSand& m, double p) { return m.LimitVoidRatiosAt(p).critical; }, psi_c);
  }
  const bool rising = std::cos(psi_epsilon) > 0;  // compression: p rises
  const double start = rising ? lo / 10.0 : hi * 10.0;
  const ModelState initial = InitialStateFromOcr(model, start, 0.0, 1.0);
  // One stage per distinct target, each ending exactly at its p (the stop's
  // root finding), so that the states are smooth in the parameters (no
  // interpolation between records under the fit's central differences).
  std::vector<size_t> order(targets.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return rising ? targets[a] < targets[b] : targets[a] > targets[b];
  });
  std::vector<LoadingStage> stages;
  std::vector<int> stage_of(targets.size(), -1);
  for (size_t k : order) {
    if (stages.empty() || targets[k] != stages.back().stops.front().value) {
      LoadingStage stage = LoadingStage::Proportional(psi_epsilon, 1.0, 50.0);
      stage.stops.push_back({StopKind::kMeanStress, targets[k]});
      stage.output_points = 1;
      stages.push_back(stage);
    }
    stage_of[k] = static_cast<int>(stages.size()) - 1;
  }
  const ElementTestResult result = ElementTest(model, options.sand_paths).Run(initial, stages);
  std::vector<const ElementTestRecord*> ends(stages.size(), nullptr);
  for (const ElementTestRecord& record : result.history) {
    if (record.stage >= 0 && record.stage < static_cast<int>(ends.size())) {
      ends[record.stage] = &record;
    }
  }
  for (size_t k = 0; k < targets.size(); ++k) {
    const int j = stage_of[k];
    const bool reached = result.summary.success() &&
                         static_cast<int>(result.summary.stages.size()) > j &&
                         result.summary.stages[j].stop != "duration" && ends[j] != nullptr;
    if (!reached) {
      *why = fmt::format(
          "the sand model's path at psi_epsilon = {:.4g} deg from p = {:.4g} kPa does not reach "
          "p = {:.4g} kPa ({})",
          psi_epsilon / kDegree, start, targets[k], result.summary.Report());
      return false;
    }
    const AxisymmetricStress s = RecordStress(*ends[j]);
    (*out)[k].psi_sigma = s.psi();
    (*out)[k].ln_volume = std::log1p(ends[j]->void_ratio);
    (*out)[k].ln_ocr =
        std::log(std::max(model.EquivalentPressure(ends[j]->void_ratio), 1e-300) / targets[k]);
  }
  return true;
}

}  // namespace

AsymptotePredictor::AsymptotePredictor(ModelKind kind, const PredictorOptions& options)
    : kind_(kind), options_(options) {
  std::string why;
  GRANASYM_CHECK(options_.IsValid(&why)) << why;
}

bool AsymptotePredictor::PredictAtPressures(const std::vector<double>& parameters,
                                            const std::vector<double>& psi_epsilons,
                                            const std::vector<double>& mean_stresses,
                                            std::vector<StatePrediction>* states,
                                            std::string* why) const {
  GRANASYM_CHECK(psi_epsilons.size() == mean_stresses.size());
  const std::unique_ptr<ConstitutiveModel> model = MakeModel(kind_, parameters, why);
  if (!model) return false;
  // The closed forms on the axes are Bauer's limit void ratios (SandPath).
  const auto* sand = dynamic_cast<const HypoplasticSand*>(model.get());
  GRANASYM_CHECK(sand != nullptr) << "PredictAtPressures: sand model only";
  states->assign(psi_epsilons.size(), StatePrediction());
  std::vector<bool> done(psi_epsilons.size(), false);
  for (size_t k = 0; k < psi_epsilons.size(); ++k) {
    if (done[k]) continue;
    std::vector<size_t> members;
    std::vector<double> targets;
    for (size_t j = k; j < psi_epsilons.size(); ++j) {
      if (psi_epsilons[j] == psi_epsilons[k]) {
        members.push_back(j);
        targets.push_back(mean_stresses[j]);
        done[j] = true;
      }
    }
    std::vector<StatePrediction> path;
    if (!SandPath(*sand, psi_epsilons[k], targets, options_, &path, why)) return false;
    for (size_t m = 0; m < members.size(); ++m) (*states)[members[m]] = path[m];
  }
  return true;
}

bool AsymptotePredictor::Predict(const std::vector<double>& parameters,
                                 const std::vector<double>& psi_epsilons,
                                 const std::vector<double>& psi_sigmas,
                                 std::vector<Prediction>* by_stretching,
                                 std::vector<Prediction>* by_stress, std::string* why) const {
  if (!Traits(kind_).linear_ncl) {
    *why = fmt::format(
        "the {} model has no p-independent asymptotes (its NCL is curved in ln(1+e)-ln p): use "
        "PredictAtPressures",
        Traits(kind_).title);
    return false;
  }
  const std::unique_ptr<ConstitutiveModel> model = MakeModel(kind_, parameters, why);
  if (!model) return false;
  by_stretching->assign(psi_epsilons.size(), Prediction());
  by_stress->assign(psi_sigmas.size(), Prediction());

  const ConstitutiveModel& asymptotes = *model;
  const StressMap map = [&asymptotes](double psi, Prediction* out, std::string* w) {
    return AsymptoteOf(asymptotes, psi, out, w);
  };
  for (size_t k = 0; k < psi_sigmas.size(); ++k) {
    const double psi = std::min(std::max(psi_sigmas[k], kLowestPsiSigma), kHighestPsiSigma);
    if (!map(psi, &(*by_stress)[k], why)) return false;
  }
  if (psi_epsilons.empty()) return true;

  if (options_.method == AsymptoteMethod::kIntegrated) {
    const ModelState initial = InitialStateFromOcr(*model, options_.initial_mean_stress, 0.0, 1.0);
    for (size_t k = 0; k < psi_epsilons.size(); ++k) {
      const IntegratedAsymptote asymptote =
          IntegrateAsymptote(*model, initial, psi_epsilons[k], options_.search);
      if (!asymptote.found) {
        *why = fmt::format("no asymptote found at psi_epsilon = {} deg: {}",
                           psi_epsilons[k] / kDegree, asymptote.summary.Report());
        return false;
      }
      Prediction& out = (*by_stretching)[k];
      out.psi_epsilon = psi_epsilons[k];
      out.psi_sigma = asymptote.state.psi_sigma;
      out.ln_ocr = std::log(asymptote.state.ocr);
    }
    return true;
  }

  std::vector<Prediction> grid;
  if (!Curve(parameters, options_.curve_points, &grid, why)) return false;
  for (size_t k = 0; k < psi_epsilons.size(); ++k) {
    if (!Invert(map, grid, psi_epsilons[k], options_.psi_sigma_tolerance, &(*by_stretching)[k],
                why)) {
      return false;
    }
  }
  return true;
}

bool AsymptotePredictor::Curve(const std::vector<double>& parameters, int points,
                               std::vector<Prediction>* curve, std::string* why) const {
  if (!Traits(kind_).linear_ncl) {
    *why = fmt::format("the {} model has no analytic asymptotic state boundary surface",
                       Traits(kind_).title);
    return false;
  }
  const std::unique_ptr<ConstitutiveModel> model = MakeModel(kind_, parameters, why);
  if (!model) return false;
  curve->assign(static_cast<size_t>(points), Prediction());
  for (int i = 0; i < points; ++i) {
    const double psi = kLowestPsiSigma + (kHighestPsiSigma - kLowestPsiSigma) * i / (points - 1);
    if (!AsymptoteOf(*model, psi, &(*curve)[static_cast<size_t>(i)], why)) return false;
  }
  return true;
}

}  // namespace granasym::calibration
