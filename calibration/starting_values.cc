// Regressions for the starting values.
#include "calibration/starting_values.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "common/state_measures.h"
#include "common/statistics.h"
#include "constitutive/model_traits.h"

namespace granasym::calibration {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double FrictionAngleFromPsiSigma(double psi_sigma) {
  const double m = 3.0 * std::tan(psi_sigma) / std::sqrt(2.0);
  return std::asin(3.0 * m / (6.0 + m)) / kDegree;
}

// The key of the parameter that the estimate for `role` starts (the first
// such parameter of the models' traits).
const char* KeyStartedBy(ParameterStart role) {
  for (ModelKind kind : EnumValues<ModelKind>()) {
    for (const FittedParameter& p : Traits(kind).parameters) {
      if (p.start == role) return p.traits.key;
    }
  }
  return ToString(role);
}

std::string Line(const char* name, const Estimate& e) {
  if (!e.from_data) return fmt::format("  {:<12} {:>10.5g}  (assumed: {})", name, e.value, e.note);
  return fmt::format("  {:<12} {:>10.5g} ± {:<10.3g} ({} points: {})", name, e.value,
                     e.standard_error, e.points, e.note);
}

}  // namespace

std::string StartingValues::Report() const {
  return "starting values from the data (± one standard error):\n" +
         Line(KeyStartedBy(ParameterStart::kCslStressRatio), critical_friction_angle_deg) + "\n" +
         Line(KeyStartedBy(ParameterStart::kNclSlope), lambda_star) + "\n" +
         Line(KeyStartedBy(ParameterStart::kUnloadingSlope), kappa_star) + "\n" +
         Line(KeyStartedBy(ParameterStart::kNclIntercept), n_intercept);
}

StartingValues EstimateStartingValues(const std::vector<StateDataset>& datasets) {
  StartingValues start;
  std::vector<double> ln_p, ln_v, csl_psi, csl_ln_p, csl_ln_v;
  // Unloading branches pooled with one intercept each: centre each branch.
  std::vector<double> unload_x, unload_y;
  for (const StateDataset& dataset : datasets) {
    std::vector<double> bx, by;
    for (const AsymptoticStatePoint& point : dataset.points) {
      if (point.kind == StateKind::kNcl) {
        ln_p.push_back(std::log(point.mean_stress));
        ln_v.push_back(std::log1p(point.void_ratio));
      } else if (point.kind == StateKind::kCsl) {
        csl_psi.push_back(point.psi_sigma);
        csl_ln_p.push_back(std::log(point.mean_stress));
        csl_ln_v.push_back(std::log1p(point.void_ratio));
      } else if (point.kind == StateKind::kUnloading) {
        bx.push_back(std::log(point.mean_stress));
        by.push_back(std::log1p(point.void_ratio));
      }
    }
    if (bx.size() >= 2) {
      double mx = 0, my = 0;
      for (size_t i = 0; i < bx.size(); ++i) {
        mx += bx[i] / bx.size();
        my += by[i] / by.size();
      }
      for (size_t i = 0; i < bx.size(); ++i) {
        unload_x.push_back(bx[i] - mx);
        unload_y.push_back(by[i] - my);
      }
    }
  }

  const LineFit ncl = FitLine(ln_p, ln_v);
  if (std::isfinite(ncl.slope) && ncl.slope < 0) {
    start.lambda_star = {true, -ncl.slope, ncl.slope_error, ncl.points,
                         "NCL regression in ln(1+e)-ln p"};
    start.n_intercept = {true, ncl.intercept, ncl.intercept_error, ncl.points,
                         "NCL regression at p_r = 1 kPa"};
  } else {
    // The NCL gives no slope (its states at one p, as a rate study's
    // ψ_ε = 0° paths, which all end at the same stress cap): the CSL's, which
    // is parallel to it in the three models, when it falls; else assumed.
    // The intercept then goes through the NCL points at that slope.
    const std::string why = ln_p.size() < 2 ? "fewer than 2 NCL points"
                                            : "NCL points do not decrease in ln(1+e) with ln p";
    const LineFit csl = FitLine(csl_ln_p, csl_ln_v);
    if (std::isfinite(csl.slope) && csl.slope < 0) {
      start.lambda_star = {true, -csl.slope, csl.slope_error, csl.points,
                           why + ": the CSL regression in ln(1+e)-ln p (parallel to the NCL)"};
    } else {
      start.lambda_star = {false, 0.1, kNaN, ncl.points, why};
    }
    if (!ln_p.empty()) {
      start.n_intercept = {false, Mean(ln_v) + start.lambda_star.value * Mean(ln_p), kNaN,
                           ncl.points, why + ": through their mean at the starting lambda_star"};
    } else {
      start.n_intercept = {false, 1.0, kNaN, ncl.points, why};
    }
  }

  if (!csl_psi.empty()) {
    double mean = 0;
    for (double psi : csl_psi) mean += psi / csl_psi.size();
    double error = kNaN;
    if (csl_psi.size() > 1) {
      double ss = 0;
      for (double psi : csl_psi) ss += (psi - mean) * (psi - mean);
      const double sem = std::sqrt(ss / (csl_psi.size() - 1) / csl_psi.size());
      // Propagate through φ_c(ψ_σ) by a central difference.
      const double h = 1e-6;
      const double slope =
          (FrictionAngleFromPsiSigma(mean + h) - FrictionAngleFromPsiSigma(mean - h)) / (2 * h);
      error = std::abs(slope) * sem;
    }
    start.critical_friction_angle_deg = {true, FrictionAngleFromPsiSigma(mean), error,
                                         static_cast<int>(csl_psi.size()),
                                         "mean critical stress ratio of the CSL points"};
  } else {
    start.critical_friction_angle_deg = {false, 25.0, kNaN, 0, "no CSL points"};
  }

  const LineFit unloading = FitLine(unload_x, unload_y);
  if (std::isfinite(unloading.slope) && unloading.slope < 0) {
    start.kappa_star = {true, -unloading.slope, unloading.slope_error, unloading.points,
                        "unloading branches in ln(1+e)-ln p"};
  } else {
    const double lambda = start.lambda_star.value;
    start.kappa_star = {false, lambda / 5.0, kNaN, unloading.points,
                        unload_x.empty() ? "no unloading branch: lambda_star/5"
                                         : "unloading branch without swelling: lambda_star/5"};
  }
  return start;
}

}  // namespace granasym::calibration
