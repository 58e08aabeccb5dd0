// Profile likelihoods: grids, warm-started refits, crossings and flatness.
#include "calibration/profile_likelihood.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>

#include "common/error.h"
#include "common/statistics.h"

namespace granasym::calibration {

namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
// z_{0.975}²: χ²_{1; 0.95}.
constexpr double kChiSquare1 = 1.959963984540054 * 1.959963984540054;
// A side ends once the statistic passes this multiple of the threshold.
constexpr double kStopFactor = 4.0;
// Where a step fails (the model undefined), the side's end is located by
// this many bisections: within 1/64 of the failed step.
constexpr int kDomainBisections = 6;

// The profile of one parameter.
class Profiler {
 public:
  Profiler(const CalibrationProblem& problem, const FitResult& fit,
           const CeresFitter::Options& ceres, const ProfileOptions& options, double threshold,
           double residual_variance)
      : problem_(problem),
        fit_(fit),
        ceres_(ceres),
        options_(options),
        threshold_(threshold),
        residual_variance_(residual_variance) {
    ceres_ = CeresFitter::CostRefitOptions(ceres, options.fast_refits);
  }

  ParameterProfile Run(int parameter) const {
    const auto t0 = std::chrono::steady_clock::now();
    const ParameterSpec& spec = problem_.parameters().specs()[parameter];
    ParameterProfile profile;
    profile.parameter = parameter;
    profile.name = spec.name;
    profile.units = spec.units;
    profile.log_scale = ProfiledOnLogScale(spec);
    profile.fitted = spec.free;
    profile.optimum = fit_.values[parameter];
    ProfilePoint center;
    center.value = profile.optimum;
    center.cost = fit_.summary.final_cost;
    center.converged = true;
    center.values = fit_.values;
    std::vector<ProfilePoint> below, above;
    Side(parameter, -1, &profile, &below);
    Side(parameter, +1, &profile, &above);
    std::reverse(below.begin(), below.end());
    profile.points = std::move(below);
    profile.points.push_back(center);
    profile.points.insert(profile.points.end(), above.begin(), above.end());
    profile.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return profile;
  }

 private:
  double U(bool log_scale, double value) const { return log_scale ? std::log(value) : value; }
  double X(bool log_scale, double u) const { return log_scale ? std::exp(u) : u; }

  // The grid's first reach on ln θ or θ: 2·√threshold standard errors where
  // the fit reports one, else the whole reach.
  double FirstReach(int parameter, bool log_scale, double reach_max) const {
    for (size_t k = 0; k < fit_.free_indices.size(); ++k) {
      if (fit_.free_indices[k] != parameter || !fit_.Reported(k)) continue;
      const double se = fit_.standard_errors[k];
      const double value = fit_.values[parameter];
      const double se_u = log_scale ? se / value : se;
      if (se_u > 0 && std::isfinite(se_u)) {
        return std::min(reach_max, 2.0 * std::sqrt(threshold_) * se_u);
      }
    }
    return reach_max;
  }

  // One side (`sign` −1 below, +1 above) of the profile, walking outwards.
  void Side(int parameter, int sign, ParameterProfile* profile,
            std::vector<ProfilePoint>* points) const {
    const ParameterSpec& spec = problem_.parameters().specs()[parameter];
    const bool log_scale = profile->log_scale;
    const double u0 = U(log_scale, profile->optimum);
    const double limit = U(log_scale, sign < 0 ? spec.lower : spec.upper);
    double reach_max = std::max(0.0, sign * (limit - u0));
    bool decade_limited = false;
    if (log_scale && reach_max > std::log(10.0)) {
      reach_max = std::log(10.0);
      decade_limited = true;
    }
    ProfileEnd end = decade_limited ? ProfileEnd::kDecade : ProfileEnd::kBound;
    if (reach_max <= 1e-12 * (1.0 + std::abs(u0))) {
      (sign < 0 ? profile->lower_end : profile->upper_end) = end;  // at the bound already
      return;
    }
    const double first = FirstReach(parameter, log_scale, reach_max);
    std::vector<double> distances;
    const int k_points = options_.points_per_side;
    for (int j = 1; j <= k_points; ++j) distances.push_back(first * j / k_points);
    const size_t grid = distances.size();
    for (int e = 1; e <= options_.max_extension_points && distances.back() < reach_max; ++e) {
      distances.push_back(e == options_.max_extension_points
                              ? reach_max
                              : std::min(reach_max, first * std::pow(2.0, e)));
    }
    std::vector<double> warm = fit_.values;
    bool crossed = false, failed = false;
    // A point of the side at `distance`, refitted from the last point (else
    // from the fit); false, with the failure recorded, where the model is
    // undefined there or the refit fails.
    const auto step = [&](double distance, bool exact_bound) {
      ProfilePoint point;
      point.value =
          exact_bound ? (sign < 0 ? spec.lower : spec.upper) : X(log_scale, u0 + sign * distance);
      std::string why;
      ++profile->refits;
      if (!Refit(parameter, point.value, warm, &point, &why) &&
          (warm == fit_.values || !Refit(parameter, point.value, fit_.values, &point, &why))) {
        profile->failure = fmt::format("{} = {:.6g}: {}", spec.name, point.value, why);
        return false;
      }
      profile->evaluations += point.evaluations;
      warm = point.values;
      points->push_back(point);
      const double statistic = 2.0 * (point.cost - fit_.summary.final_cost) / residual_variance_;
      crossed = crossed || statistic >= threshold_;
      return true;
    };
    for (size_t j = 0; j < distances.size(); ++j) {
      // Beyond the grid only while the profile has not crossed the threshold.
      if (j >= grid && crossed) break;
      const bool exact_bound =
          j + 1 == distances.size() && !decade_limited && distances[j] == reach_max;
      if (!step(distances[j], exact_bound)) {
        failed = true;
        // The model's domain ends between the last good distance and this
        // one (an ordering constraint such as e_d0 < e_c0, or f_b > 0):
        // bisect towards it, so that the side ends at the edge, or crosses
        // the threshold before it, rather than where a coarse grid step
        // happened to jump over it.
        double good = j == 0 ? 0.0 : distances[j - 1], bad = distances[j];
        for (int h = 0; h < kDomainBisections && !crossed; ++h) {
          const double middle = 0.5 * (good + bad);
          (step(middle, false) ? good : bad) = middle;
        }
        if (crossed) failed = false;
        break;
      }
      const double statistic =
          2.0 * (points->back().cost - fit_.summary.final_cost) / residual_variance_;
      if (statistic >= kStopFactor * threshold_) break;
    }
    if (failed) {
      end = ProfileEnd::kDomain;
    } else if (crossed) {
      end = ProfileEnd::kCrossed;
    }
    (sign < 0 ? profile->lower_end : profile->upper_end) = end;
  }

  // The other free parameters re-optimised with `parameter` fixed at `value`,
  // starting from `warm` (a full vector).
  bool Refit(int parameter, double value, const std::vector<double>& warm, ProfilePoint* point,
             std::string* why) const {
    ModelParameters parameters = problem_.parameters();
    std::vector<ParameterSpec>& specs = parameters.mutable_specs();
    specs[parameter].free = false;
    specs[parameter].value = value;
    for (size_t i = 0; i < specs.size(); ++i) {
      if (specs[i].free)
        specs[i].value = std::min(std::max(warm[i], specs[i].lower), specs[i].upper);
    }
    try {
      // The whole problem (paths and group weights included) with one parameter fixed.
      const CalibrationProblem sub = problem_.WithParameters(std::move(parameters));
      if (sub.num_free() == 0) {
        point->cost = sub.Cost({});
        point->values = sub.parameters().Values();
        point->converged = std::isfinite(point->cost);
        if (!point->converged) *why = "the model is undefined there";
        return point->converged;
      }
      const FitResult refit = CeresFitter(ceres_).Fit(sub);
      point->evaluations = refit.summary.evaluations;
      if (!refit.summary.success() || !std::isfinite(refit.summary.final_cost)) {
        *why = refit.summary.message;
        return false;
      }
      point->cost = refit.summary.final_cost;
      point->values = refit.values;
      point->converged = refit.summary.termination == FitTermination::kConverged;
      return true;
    } catch (const std::exception& error) {
      *why = error.what();
      return false;
    }
  }

  const CalibrationProblem& problem_;
  const FitResult& fit_;
  CeresFitter::Options ceres_;
  ProfileOptions options_;
  double threshold_, residual_variance_;
};

// The statistics against `reference`, the interval ends and the flat range.
void Finish(double reference, double residual_variance, double threshold,
            ParameterProfile* profile) {
  for (ProfilePoint& point : profile->points) {
    point.statistic = 2.0 * (point.cost - reference) / residual_variance;
  }
  const std::vector<ProfilePoint>& points = profile->points;
  size_t center = 0;
  for (size_t j = 0; j < points.size(); ++j) {
    if (points[j].value == profile->optimum) center = j;
  }
  const auto u = [&](double x) { return profile->log_scale ? std::log(x) : x; };
  const auto x = [&](double v) { return profile->log_scale ? std::exp(v) : v; };
  // Walks from the optimum to the first point at or above the threshold.
  const auto crossing = [&](int step, ProfileEnd* end) {
    for (int j = static_cast<int>(center) + step; j >= 0 && j < static_cast<int>(points.size());
         j += step) {
      const ProfilePoint &a = points[j - step], &b = points[j];
      if (b.statistic < threshold) continue;
      *end = ProfileEnd::kCrossed;
      const double da = std::min(a.statistic, threshold);
      const double f = b.statistic > da ? (threshold - da) / (b.statistic - da) : 1.0;
      return x(u(a.value) + f * (u(b.value) - u(a.value)));
    }
    // Recomputed against a lower reference, a side's last point may lie below it.
    if (*end == ProfileEnd::kCrossed) *end = ProfileEnd::kBound;
    return kNan;
  };
  profile->lower = crossing(-1, &profile->lower_end);
  profile->upper = crossing(+1, &profile->upper_end);
  profile->flat_low = profile->flat_high = profile->optimum;
  for (const ProfilePoint& point : points) {
    if (point.statistic >= threshold) continue;
    profile->flat_low = std::min(profile->flat_low, point.value);
    profile->flat_high = std::max(profile->flat_high, point.value);
  }
}

}  // namespace

bool ProfileOptions::IsValid(std::string* why) const {
  if (points_per_side < 2 || points_per_side > 50) {
    *why = fmt::format("profile points_per_side = {} must be in [2, 50]", points_per_side);
    return false;
  }
  if (max_extension_points < 1 || max_extension_points > 20) {
    *why =
        fmt::format("profile max_extension_points = {} must be in [1, 20]", max_extension_points);
    return false;
  }
  if (max_restarts < 0 || max_restarts > 10) {
    *why = fmt::format("profile_restarts = {} must be in [0, 10]", max_restarts);
    return false;
  }
  if (!(restart_drop > 0 && restart_drop <= 10)) {
    *why = fmt::format("profile restart_drop = {} must be in (0, 10]", restart_drop);
    return false;
  }
  if (threads < 0) {
    *why = fmt::format("profile threads = {} must be >= 0 (0: one per parameter)", threads);
    return false;
  }
  return true;
}

bool ProfiledOnLogScale(const ParameterSpec& spec) {
  return spec.lower > 0 && spec.upper >= 100.0 * spec.lower;
}

bool ParameterProfile::flat() const {
  if (lower_end != ProfileEnd::kCrossed || upper_end != ProfileEnd::kCrossed) return true;
  return log_scale && flat_low > 0 && flat_high >= 10.0 * flat_low;
}

std::string ParameterProfile::Text() const {
  const auto end_text = [](ProfileEnd end) -> std::string {
    switch (end) {
      case ProfileEnd::kCrossed:
        return "";
      case ProfileEnd::kBound:
        return " (bound)";
      case ProfileEnd::kDecade:
        return " (a decade on)";
      case ProfileEnd::kDomain:
        return " (model undefined or refit failed beyond)";
    }
    return "";
  };
  if (!flat()) {
    return fmt::format("{}: [{:.6g}, {:.6g}]", name, lower, upper);
  }
  // A side that crosses the threshold ends at its crossing.
  return fmt::format("{}: flat from {:.6g}{} to {:.6g}{}: not determined", name,
                     lower_end == ProfileEnd::kCrossed ? lower : flat_low, end_text(lower_end),
                     upper_end == ProfileEnd::kCrossed ? upper : flat_high, end_text(upper_end));
}

ProfileSet ProfileLikelihood(const CalibrationProblem& problem, const FitResult& fit,
                             const std::vector<int>& also, const CeresFitter::Options& ceres,
                             const ProfileOptions& options) {
  std::string why;
  GRANASYM_CHECK(options.IsValid(&why)) << why;
  GRANASYM_CHECK(fit.summary.success() && fit.values.size() == problem.parameters().specs().size())
      << "profiles need a successful fit";
  const auto t0 = std::chrono::steady_clock::now();
  ProfileSet set;
  set.fit_cost = fit.summary.final_cost;
  const bool scaled = ceres.uncertainty.scale_by_residual_variance;
  const int dof = problem.num_residuals() - problem.num_free();
  set.residual_variance = scaled ? 2.0 * fit.summary.final_cost / std::max(1, dof) : 1.0;
  if (!(set.residual_variance > 0)) set.residual_variance = 1.0;  // an exact fit
  set.threshold = scaled ? std::pow(StudentQuantile(0.975, std::max(1, dof)), 2) : kChiSquare1;
  set.statistic = scaled ? fmt::format(
                               "D = 2 (cost - cost_min) / s^2 with s^2 = {:.4g} (the residual "
                               "variance), 95 % where D < t^2(0.975, {}) = {:.4g}",
                               set.residual_variance, dof, set.threshold)
                         : fmt::format(
                               "D = 2 (cost - cost_min) (uncertainties as standard deviations), "
                               "95 % where D < chi^2(1; 0.95) = {:.4g}",
                               set.threshold);
  std::vector<int> parameters = problem.free_indices();
  for (int i : also) {
    if (std::find(parameters.begin(), parameters.end(), i) == parameters.end()) {
      parameters.push_back(i);
    }
  }
  std::sort(parameters.begin(), parameters.end());
  const Profiler profiler(problem, fit, ceres, options, set.threshold, set.residual_variance);
  set.profiles.resize(parameters.size());
  const int hardware = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  set.threads = std::max(1, std::min(static_cast<int>(parameters.size()),
                                     options.threads > 0 ? options.threads : hardware));
  std::atomic<size_t> next{0};
  std::vector<std::string> errors(parameters.size());
  const auto work = [&] {
    for (size_t j = next++; j < parameters.size(); j = next++) {
      try {
        set.profiles[j] = profiler.Run(parameters[j]);
      } catch (const std::exception& error) {
        errors[j] = error.what();
      }
    }
  };
  std::vector<std::thread> threads;
  for (int t = 1; t < set.threads; ++t) threads.emplace_back(work);
  work();
  for (std::thread& thread : threads) thread.join();
  for (const std::string& error : errors) {
    if (!error.empty()) throw RuntimeError("profile likelihood: " + error);
  }
  for (ParameterProfile& profile : set.profiles) {
    // cost_min: the fit's, or the profile's own least cost where lower.
    profile.reference_cost = set.fit_cost;
    profile.least_value = profile.optimum;
    for (const ProfilePoint& point : profile.points) {
      if (point.cost < profile.reference_cost) {
        profile.reference_cost = point.cost;
        profile.least_value = point.value;
      }
    }
    const double drop = 2.0 * (set.fit_cost - profile.reference_cost) / set.residual_variance;
    if (profile.fitted && drop > 0.1 * set.threshold) {
      set.warnings.push_back(fmt::format(
          "profile_lower_cost: the profile of {} reaches cost {:.6g} at {} = {:.6g}, below the "
          "fit's {:.6g} (D = {:.3g}): the fit is not at the least-squares optimum; its profile is "
          "taken against the lower cost",
          profile.name, profile.reference_cost, profile.name, profile.least_value, set.fit_cost,
          drop));
    }
    Finish(profile.reference_cost, set.residual_variance, set.threshold, &profile);
    if ((profile.lower_end == ProfileEnd::kDomain || profile.upper_end == ProfileEnd::kDomain) &&
        !profile.failure.empty()) {
      set.warnings.push_back("profile_refit_failed: " + profile.failure);
    }
  }
  set.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return set;
}

std::string ProfileRestart::Text() const {
  return fmt::format(
      "refitted from the {} profile ({} = {:.6g}, profile cost {:.6g}): cost {:.6g} "
      "-> {:.6g}{}",
      parameter, parameter, value, profile_cost, cost_before, cost_after,
      kept ? "" : " (not lower: the fit is kept)");
}

RefittedProfiles ProfileAndRefit(const CalibrationProblem& problem, const FitResult& fit,
                                 const std::vector<int>& also, const CeresFitter::Options& ceres,
                                 const ProfileOptions& options) {
  RefittedProfiles out;
  out.fit = fit;
  for (int round = 0;; ++round) {
    out.profiles = ProfileLikelihood(problem, out.fit, also, ceres, options);
    if (round >= options.max_restarts) break;
    // The least cost over the fitted parameters' profiles (an undetermined
    // parameter's profile moves a fixed parameter: not this problem's fit).
    const ParameterProfile* best = nullptr;
    const ProfilePoint* best_point = nullptr;
    for (const ParameterProfile& profile : out.profiles.profiles) {
      if (!profile.fitted) continue;
      for (const ProfilePoint& point : profile.points) {
        if (!std::isfinite(point.cost)) continue;
        if (best_point == nullptr || point.cost < best_point->cost) {
          best = &profile;
          best_point = &point;
        }
      }
    }
    const double fit_cost = out.fit.summary.final_cost;
    if (best_point == nullptr ||
        2.0 * (fit_cost - best_point->cost) / out.profiles.residual_variance <=
            options.restart_drop * out.profiles.threshold) {
      break;
    }
    ProfileRestart restart;
    restart.parameter = best->name;
    restart.value = best_point->value;
    restart.profile_cost = best_point->cost;
    restart.cost_before = fit_cost;
    std::vector<double> start;
    for (int i : problem.free_indices()) start.push_back(best_point->values[i]);
    FitResult refit;
    try {
      refit = CeresFitter(ceres).Fit(problem, start);
    } catch (const std::exception&) {
      refit.summary.termination = FitTermination::kFailure;
    }
    const bool lower = refit.summary.success() && std::isfinite(refit.summary.final_cost) &&
                       refit.summary.final_cost < fit_cost;
    restart.cost_after = refit.summary.success() ? refit.summary.final_cost
                                                 : std::numeric_limits<double>::infinity();
    restart.kept = lower;
    out.restarts.push_back(restart);
    if (!lower) break;
    out.fit = std::move(refit);
  }
  return out;
}

std::string ProfilesCsv(const ProfileSet& set) {
  std::string csv =
      "parameter,value,cost,statistic,threshold,converged,log_scale,optimum,ci95_low,ci95_high,"
      "flat\n";
  const auto number = [](double v) { return std::isfinite(v) ? fmt::format("{:.10g}", v) : ""; };
  for (const ParameterProfile& profile : set.profiles) {
    for (const ProfilePoint& point : profile.points) {
      csv +=
          fmt::format("{},{},{},{},{:.10g},{},{},{},{},{},{}\n", profile.name, number(point.value),
                      number(point.cost), number(point.statistic), set.threshold,
                      point.converged ? 1 : 0, profile.log_scale ? 1 : 0, number(profile.optimum),
                      number(profile.lower), number(profile.upper), profile.flat() ? 1 : 0);
    }
  }
  return csv;
}

std::string ProfileParametersCsv(const ProfileSet& set) {
  std::string csv =
      "parameter,log_scale,optimum,threshold,flat,low,high,low_crossed,high_crossed\n";
  for (const ParameterProfile& p : set.profiles) {
    const bool low = p.lower_end == ProfileEnd::kCrossed,
               high = p.upper_end == ProfileEnd::kCrossed;
    csv +=
        fmt::format("{},{},{:.10g},{:.10g},{},{:.10g},{:.10g},{},{}\n", p.name, p.log_scale ? 1 : 0,
                    p.optimum, set.threshold, p.flat() ? 1 : 0, low ? p.lower : p.flat_low,
                    high ? p.upper : p.flat_high, low ? 1 : 0, high ? 1 : 0);
  }
  return csv;
}

std::string ProfilesText(const ProfileSet& set) {
  int refits = 0, flat = 0;
  long evaluations = 0;
  for (const ParameterProfile& profile : set.profiles) {
    refits += profile.refits;
    evaluations += profile.evaluations;
    flat += profile.flat() ? 1 : 0;
  }
  std::string s = fmt::format(
      "profile likelihood: {} parameters, {} refits ({} evaluations), {:.2f} s on {} thread{}; {} "
      "flat (not determined)\n  {}\n",
      set.profiles.size(), refits, evaluations, set.wall_seconds, set.threads,
      set.threads == 1 ? "" : "s", flat, set.statistic);
  s += fmt::format("  {:<14} {:>12} {:>28}  {:>6}  {}\n", "parameter", "value",
                   "profile 95 % interval", "points", "profile");
  for (const ParameterProfile& profile : set.profiles) {
    const std::string interval =
        profile.flat() ? std::string("—")
                       : fmt::format("[{:.6g}, {:.6g}]", profile.lower, profile.upper);
    const std::string shape =
        profile.flat() ? profile.Text().substr(profile.name.size() + 2) : "determined";
    const double drop = 2.0 * (set.fit_cost - profile.reference_cost) / set.residual_variance;
    const std::string least =
        !profile.fitted && drop > 1e-3 * set.threshold
            ? fmt::format("; least cost at {:.6g}, D = {:.3g} at its fixed value",
                          profile.least_value, drop)
            : "";
    s += fmt::format(
        "  {:<14} {:>12.6g} {:>28}  {:>6}  {}{}{}\n", profile.name, profile.optimum, interval,
        profile.points.size(), shape, profile.log_scale ? " (log grid)" : "",
        profile.fitted ? "" : " (fixed as undetermined; profiled from its value" + least + ")");
  }
  for (const std::string& w : set.warnings) s += "  WARNING: " + w + "\n";
  return s;
}

}  // namespace granasym::calibration
