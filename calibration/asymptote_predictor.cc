// Analytic and integrated asymptotic states of the calibrated models.
#include "calibration/asymptote_predictor.h"

#include <fmt/format.h>

#include <cmath>
#include <functional>
#include <memory>

#include "calibration/model_parameters.h"
#include "common/error.h"
#include "common/state_measures.h"
#include "constitutive/element_test.h"
#include "constitutive/hypoplastic_clay.h"
#include "constitutive/modified_cam_clay.h"

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

// Modified Cam clay on the Roscoe surface, see the header.
bool CamClayAsymptote(const std::vector<double>& v, double psi_sigma, Prediction* out,
                      std::string*) {
  const double m = CriticalStateRatio(v[kCriticalFrictionAngle] * kDegree);
  const double lambda = v[kLambdaStar], kappa = v[kKappaStar], nu = v[kShearParameter];
  const double eta = 3.0 * std::tan(psi_sigma) / std::sqrt(2.0);
  const double c = 2.0 * (1.0 + nu) / (9.0 * (1.0 - 2.0 * nu));
  const double m2_minus = m * m - eta * eta;
  const double rate_v = lambda * m2_minus;
  const double rate_s = eta * (kappa * c * m2_minus + 2.0 * (lambda - kappa));
  out->psi_sigma = psi_sigma;
  out->psi_epsilon = std::atan2(3.0 / std::sqrt(2.0) * rate_s, rate_v);
  out->ln_ocr = (1.0 - kappa / lambda) * std::log1p(eta * eta / (m * m));
  out->clamped = false;
  return true;
}

bool HypoplasticAsymptote(const HypoplasticClay& model, double psi_sigma, Prediction* out,
                          std::string* why) {
  AsymptoticState state;
  if (!AnalyticAsymptoteForStress(model, psi_sigma, &state, why)) return false;
  out->psi_sigma = psi_sigma;
  out->psi_epsilon = state.psi_epsilon;
  out->ln_ocr = std::log(state.ocr);
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
    double lo = a.psi_sigma, hi = b.psi_sigma;
    double g_lo = a.psi_epsilon - target, g_hi = b.psi_epsilon - target;
    Prediction best = std::abs(g_lo) < std::abs(g_hi) ? a : b;
    int side = 0;
    for (int iteration = 0; iteration < 100 && hi - lo > tolerance; ++iteration) {
      double x = (g_hi * lo - g_lo * hi) / (g_hi - g_lo);
      if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
      Prediction mid;
      if (!map(x, &mid, why)) return false;
      const double g = mid.psi_epsilon - target;
      best = mid;
      if (g == 0.0) break;
      if ((g < 0) == (g_lo < 0)) {
        lo = x;
        g_lo = g;
        if (side == -1) g_hi *= 0.5;
        side = -1;
      } else {
        hi = x;
        g_hi = g;
        if (side == +1) g_lo *= 0.5;
        side = +1;
      }
    }
    *out = best;
    out->psi_epsilon = target;
    return true;
  }
  *out = grid.back();
  out->clamped = true;
  return true;
}

}  // namespace

AsymptotePredictor::AsymptotePredictor(ModelKind kind, const PredictorOptions& options)
    : kind_(kind), options_(options) {
  GRANASYM_CHECK(IsCalibrated(kind))
      << "calibration fits the clay models only, not " << ToString(kind);
  std::string why;
  GRANASYM_CHECK(options_.IsValid(&why)) << why;
}

bool AsymptotePredictor::Predict(const std::vector<double>& parameters,
                                 const std::vector<double>& psi_epsilons,
                                 const std::vector<double>& psi_sigmas,
                                 std::vector<Prediction>* by_stretching,
                                 std::vector<Prediction>* by_stress, std::string* why) const {
  const std::unique_ptr<ConstitutiveModel> model = MakeModel(kind_, parameters, why);
  if (!model) return false;
  by_stretching->assign(psi_epsilons.size(), Prediction());
  by_stress->assign(psi_sigmas.size(), Prediction());

  StressMap map;
  if (kind_ == ModelKind::kHypoplasticClay) {
    const auto* clay = static_cast<const HypoplasticClay*>(model.get());
    map = [clay](double psi, Prediction* out, std::string* w) {
      return HypoplasticAsymptote(*clay, psi, out, w);
    };
  } else {
    map = [&parameters](double psi, Prediction* out, std::string* w) {
      return CamClayAsymptote(parameters, psi, out, w);
    };
  }
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
  const std::unique_ptr<ConstitutiveModel> model = MakeModel(kind_, parameters, why);
  if (!model) return false;
  curve->assign(static_cast<size_t>(points), Prediction());
  for (int i = 0; i < points; ++i) {
    const double psi = kLowestPsiSigma + (kHighestPsiSigma - kLowestPsiSigma) * i / (points - 1);
    Prediction& out = (*curve)[static_cast<size_t>(i)];
    const bool ok =
        kind_ == ModelKind::kHypoplasticClay
            ? HypoplasticAsymptote(static_cast<const HypoplasticClay&>(*model), psi, &out, why)
            : CamClayAsymptote(parameters, psi, &out, why);
    if (!ok) return false;
  }
  return true;
}

}  // namespace granasym::calibration
