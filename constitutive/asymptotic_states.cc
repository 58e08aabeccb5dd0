// Analytic (ASBS) and integrated asymptotic states.
#include "constitutive/asymptotic_states.h"

#include <fmt/format.h>

#include <cmath>

#include "common/error.h"

namespace granasym {

namespace {
// Ends of the admissible ψ_σ range: σ_a → 0 and σ_r → 0.
const double kLowestPsiSigma = -std::atan(1.0 / std::sqrt(2.0));
const double kHighestPsiSigma = std::atan(std::sqrt(2.0));
constexpr double kRangeMargin = 1e-9;

double PsiEpsilonOf(const Vector6& stretching_tension_positive) {
  const SymTensor d = FlipSign(ToSymTensor(stretching_tension_positive));
  return AxisymmetricRate{d[0], 0.5 * (d[1] + d[2])}.psi();
}
}  // namespace

bool AnalyticAsymptoteForStress(const HypoplasticClay& model, double psi_sigma,
                                AsymptoticState* state, std::string* why) {
  HypoplasticClay::Asymptote asymptote;
  const Vector6 stress = AxisymmetricStressTensor(1.0, psi_sigma);
  if (!model.AsymptoteForStress(stress, &asymptote, why)) return false;
  state->psi_sigma = psi_sigma;
  state->psi_epsilon = PsiEpsilonOf(asymptote.stretching_direction);
  state->ocr = asymptote.ocr;
  state->stress_ratio = 3.0 * std::tan(psi_sigma) / std::sqrt(2.0);
  return true;
}

void AnalyticStretchingRange(const HypoplasticClay& model, double* lowest, double* highest) {
  AsymptoticState low, high;
  std::string why;
  AnalyticAsymptoteForStress(model, kLowestPsiSigma + kRangeMargin, &low, &why);
  AnalyticAsymptoteForStress(model, kHighestPsiSigma - kRangeMargin, &high, &why);
  *lowest = low.psi_epsilon;
  *highest = high.psi_epsilon;
}

bool AnalyticAsymptoteForStretching(const HypoplasticClay& model, double psi_epsilon,
                                    AsymptoticState* state, std::string* why) {
  // ψ_ε(ψ_σ) is continuous and increasing on the admissible range: bracket on a
  // grid (robust to mild non-monotonicity), then bisect.
  constexpr int kGrid = 400;
  double previous_psi = kLowestPsiSigma + kRangeMargin;
  AsymptoticState previous;
  if (!AnalyticAsymptoteForStress(model, previous_psi, &previous, why)) return false;
  for (int i = 1; i <= kGrid; ++i) {
    const double psi = kLowestPsiSigma + kRangeMargin +
                       (kHighestPsiSigma - kLowestPsiSigma - 2 * kRangeMargin) * i / kGrid;
    AsymptoticState current;
    if (!AnalyticAsymptoteForStress(model, psi, &current, why)) return false;
    const double g0 = previous.psi_epsilon - psi_epsilon;
    const double g1 = current.psi_epsilon - psi_epsilon;
    // A jump through ±π is not a crossing.
    if ((g0 <= 0 && g1 >= 0) && std::abs(current.psi_epsilon - previous.psi_epsilon) < kPi) {
      double lo = previous_psi, hi = psi;
      AsymptoticState mid_state = current;
      for (int iteration = 0; iteration < 200 && hi - lo > 1e-15; ++iteration) {
        const double mid = 0.5 * (lo + hi);
        if (!AnalyticAsymptoteForStress(model, mid, &mid_state, why)) return false;
        if (mid_state.psi_epsilon < psi_epsilon) {
          lo = mid;
        } else {
          hi = mid;
        }
      }
      return AnalyticAsymptoteForStress(model, 0.5 * (lo + hi), state, why);
    }
    previous = current;
    previous_psi = psi;
  }
  if (why != nullptr) {
    *why = fmt::format("psi_epsilon = {:.6g} deg has no asymptotic state for this model",
                       psi_epsilon / kDegree);
  }
  return false;
}

std::vector<AsymptoticState> AnalyticAsymptoteCurve(const HypoplasticClay& model, int points) {
  GRANASYM_CHECK(points >= 2) << "a curve needs at least two points, got " << points;
  std::vector<AsymptoticState> curve;
  for (int i = 0; i < points; ++i) {
    const double psi = kLowestPsiSigma + (kHighestPsiSigma - kLowestPsiSigma) * (i + 0.5) / points;
    AsymptoticState state;
    std::string why;
    if (AnalyticAsymptoteForStress(model, psi, &state, &why)) curve.push_back(state);
  }
  return curve;
}

bool AsymptoteSearchOptions::IsValid(std::string* why) const {
  std::string inner;
  if (!element_test.IsValid(&inner)) {
    if (why != nullptr) *why = "element_test." + inner;
    return false;
  }
  if (!(tolerance > 0 && tolerance < 1e-2)) {
    if (why != nullptr) *why = fmt::format("tolerance = {} must be in (0, 0.01)", tolerance);
    return false;
  }
  if (!(max_strain_path > 0)) {
    if (why != nullptr) *why = fmt::format("max_strain_path = {} must be > 0", max_strain_path);
    return false;
  }
  return true;
}

IntegratedAsymptote IntegrateAsymptote(const ConstitutiveModel& model, const ModelState& initial,
                                       double psi_epsilon, const AsymptoteSearchOptions& options) {
  std::string why;
  GRANASYM_CHECK(options.IsValid(&why)) << why;
  // Chunks of strain path; between chunks the state is rescaled to the initial
  // mean stress where the model allows it (the asymptote is scale free), so that
  // p neither overflows on compression paths nor underflows on extension paths.
  constexpr double kChunk = 2.0;
  constexpr double kRescaleRange = 1e3;
  const double reference_pressure = MeanStress(initial.stress);
  const ElementTest test(model, options.element_test);
  IntegratedAsymptote asymptote;
  asymptote.state.psi_epsilon = psi_epsilon;  // also when the search fails
  ModelState state = initial;
  double path = 0.0;
  ElementTestResult result;
  while (path < options.max_strain_path && !asymptote.found) {
    LoadingStage stage = LoadingStage::Proportional(
        psi_epsilon, 1.0, std::min(kChunk, options.max_strain_path - path));
    stage.stops.push_back({StopKind::kAsymptote, options.tolerance});
    stage.output_points = 1;
    result = test.Run(state, {stage});
    asymptote.summary.totals.Accumulate(result.summary.totals);
    asymptote.summary.stages.insert(asymptote.summary.stages.end(), result.summary.stages.begin(),
                                    result.summary.stages.end());
    asymptote.summary.termination = result.summary.termination;
    asymptote.summary.message = result.summary.message;
    if (!result.summary.success() || result.history.empty()) return asymptote;
    path += result.history.back().strain_path;
    asymptote.found = result.summary.stages.back().integration.root_index == 0;
    state = result.final_state;
    const double p = MeanStress(state.stress);
    if (!asymptote.found &&
        (p > kRescaleRange * reference_pressure || p < reference_pressure / kRescaleRange)) {
      model.ScaleState(reference_pressure / p, &state);
    }
  }
  const ElementTestRecord& last = result.history.back();
  const AxisymmetricStress stress = RecordStress(last);
  asymptote.state.psi_epsilon = psi_epsilon;
  asymptote.state.psi_sigma = stress.psi();
  asymptote.state.ocr = last.ocr;
  asymptote.state.stress_ratio = stress.deviator() / stress.mean();
  asymptote.strain_path = path;
  asymptote.mean_stress = stress.mean();
  asymptote.void_ratio = last.void_ratio;
  if (!asymptote.found) {
    asymptote.summary.message =
        fmt::format("no asymptote within strain path {:.3g} (criterion {:.3g} per unit strain)",
                    options.max_strain_path, options.tolerance);
  }
  return asymptote;
}

}  // namespace granasym
