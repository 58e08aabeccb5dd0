// A full hypoplastic calibration to about 100 asymptotic states (issue 4 §5):
// synthetic states of a London-clay-like parameter set at 14 stretching
// directions × 7 pressures with noise, all five parameters free, fitted by
// Ceres (from perturbed starting values) and by the NLopt CRS2 multi-start
// search with BOBYQA polish. Counters: states, residual evaluations per fit.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "calibration/calibration_problem.h"
#include "calibration/ceres_fitter.h"
#include "calibration/model_parameters.h"
#include "calibration/nlopt_fitter.h"
#include "common/state_measures.h"
#include "constitutive/asymptotic_states.h"
#include "constitutive/hypoplastic_clay.h"

namespace granasym::calibration {
namespace {

const std::vector<double> kTruth = {22.6, 0.11, 0.016, 1.375, 0.4};

StateDataset HundredStates() {
  std::string why;
  const auto model = MakeModel(ModelKind::kHypoplasticClay, kTruth, &why);
  std::mt19937 random(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  StateDataset d;
  d.name = "synthetic";
  d.origin = "benchmark";
  for (int j = 0; j < 14; ++j) {
    const double psi_e = (-40.0 + 12.0 * j) * kDegree;  // −40° … 116°
    AsymptoticState state;
    if (!AnalyticAsymptoteForStretching(static_cast<const HypoplasticClay&>(*model), psi_e, &state,
                                        &why)) {
      continue;
    }
    for (int i = 0; i < 7; ++i) {
      AsymptoticStatePoint point;
      point.kind = KindFromStretching(psi_e, 1e-6);
      point.psi_epsilon = psi_e;
      point.mean_stress = 25.0 * std::pow(2.0, i);
      point.void_ratio = std::exp(kTruth[3] - kTruth[1] * std::log(point.mean_stress * state.ocr) +
                                  0.002 * normal(random)) -
                         1;
      point.psi_sigma = state.psi_sigma + 0.3 * kDegree * normal(random);
      point.psi_sigma_uncertainty = 0.3 * kDegree;
      point.ln_volume_uncertainty = 0.002;
      point.source = "benchmark";
      d.points.push_back(point);
    }
  }
  return d;
}

ModelParameters Start() {
  ModelParameters p = ModelParameters::Defaults(ModelKind::kHypoplasticClay);
  const double factors[] = {1.15, 0.8, 1.4, 0.95, 1.3};
  for (int i = 0; i < kNumClayParameters; ++i) p.mutable_specs()[i].value = kTruth[i] * factors[i];
  return p;
}

// A full fit with the fitter's default options (Ceres; NLopt CRS2 multi-start
// with a BOBYQA polish).
template <typename Fitter>
void BM_HypoplasticFit(benchmark::State& state) {
  const CalibrationProblem problem({HundredStates()}, Start(), PredictorOptions());
  long evaluations = 0;
  double cost = 0;
  for (auto _ : state) {
    const FitResult fit = Fitter(typename Fitter::Options()).Fit(problem);
    evaluations = fit.summary.evaluations;
    cost = fit.summary.final_cost;
    benchmark::DoNotOptimize(fit.values.data());
  }
  state.counters["states"] = static_cast<double>(problem.datasets()[0].points.size());
  state.counters["residual_evaluations"] = static_cast<double>(evaluations);
  state.counters["final_cost"] = cost;
}
BENCHMARK_TEMPLATE(BM_HypoplasticFit, CeresFitter)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_HypoplasticFit, NloptFitter)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace granasym::calibration

BENCHMARK_MAIN();
