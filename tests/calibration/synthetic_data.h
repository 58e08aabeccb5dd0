// Synthetic asymptotic states of a model with known parameters plus Gaussian
// noise, for recovery tests and the benchmark. The hypoplastic states come
// from the constitutive library's own inversion (AnalyticAsymptoteForStretching),
// independent of the calibration's predictor.
#pragma once

#include <cmath>
#include <optional>
#include <random>
#include <vector>

#include "calibration/asymptote_predictor.h"
#include "calibration/model_parameters.h"
#include "calibration/state_dataset.h"
#include "common/error.h"
#include "common/state_measures.h"
#include "constitutive/asymptotic_states.h"
#include "constitutive/hypoplastic_clay.h"

namespace granasym::calibration::testing {

struct SyntheticOptions {
  std::vector<double> psi_epsilons_deg = {0, 30, 60, 80, 90, 100, 110, -30};
  std::vector<double> pressures_kpa = {50, 100, 200, 400, 800, 1600};
  double psi_sigma_noise_deg = 0.3;  // standard deviation
  double ln_volume_noise = 0.002;
  unsigned seed = 7;
  // The uncertainties the points state (by default the noise's own), e.g.
  // the DEM's 0.5° and 0.002 on data made nearly without noise.
  std::optional<double> stated_psi_sigma_deg, stated_ln_volume;
};

inline StateDataset MakeSyntheticDataset(ModelKind kind, const std::vector<double>& truth,
                                         const SyntheticOptions& options) {
  std::mt19937 random(options.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::string why;
  const std::unique_ptr<ConstitutiveModel> model = MakeModel(kind, truth, &why);
  GRANASYM_CHECK(model) << why;
  AsymptotePredictor predictor(kind, PredictorOptions());
  StateDataset dataset;
  dataset.name = "synthetic";
  dataset.origin = "synthetic";
  for (double psi_e_deg : options.psi_epsilons_deg) {
    const double psi_e = psi_e_deg * kDegree;
    double psi_sigma = 0, ln_ocr = 0;
    if (kind == ModelKind::kHypoplasticClay) {
      AsymptoticState state;
      GRANASYM_CHECK(AnalyticAsymptoteForStretching(static_cast<const HypoplasticClay&>(*model),
                                                    psi_e, &state, &why))
          << why;
      psi_sigma = state.psi_sigma;
      ln_ocr = std::log(state.ocr);
    } else {
      std::vector<Prediction> by_e, by_s;
      GRANASYM_CHECK(predictor.Predict(truth, {psi_e}, {}, &by_e, &by_s, &why)) << why;
      psi_sigma = by_e[0].psi_sigma;
      ln_ocr = by_e[0].ln_ocr;
    }
    for (double p : options.pressures_kpa) {
      AsymptoticStatePoint point;
      point.psi_epsilon = psi_e;
      point.kind = KindFromStretching(psi_e, 1e-6);
      point.mean_stress = p;
      const double ln_v = truth[kNIntercept] - truth[kLambdaStar] * (std::log(p) + ln_ocr) +
                          options.ln_volume_noise * normal(random);
      point.void_ratio = std::exp(ln_v) - 1.0;
      point.psi_sigma = psi_sigma + options.psi_sigma_noise_deg * kDegree * normal(random);
      point.psi_sigma_uncertainty =
          options.stated_psi_sigma_deg.value_or(options.psi_sigma_noise_deg) * kDegree;
      point.ln_volume_uncertainty = options.stated_ln_volume.value_or(options.ln_volume_noise);
      point.source = "synthetic";
      dataset.points.push_back(point);
    }
  }
  return dataset;
}

// A hypoplastic parameter set resembling London clay (Mašín 2005).
inline std::vector<double> LondonClay() { return {22.6, 0.11, 0.016, 1.375, 0.4}; }
// A Modified Cam clay set.
inline std::vector<double> CamClayTruth() { return {28.0, 0.09, 0.012, 1.2, 0.25}; }

}  // namespace granasym::calibration::testing
