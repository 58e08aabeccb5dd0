// Which parameters the data determine: the search's test, the freeing.
#include "calibration/identifiability.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "calibration/ceres_fitter.h"
#include "common/error.h"

namespace granasym::calibration {

std::pair<int, std::string> LeastDetermined(const CalibrationProblem& problem,
                                            const FitResult& fit) {
  std::pair<int, std::string> worst = {-1, ""};
  double worst_width = 1.0;  // interval width over bound range; ≥ 1 is undetermined
  if (fit.standard_errors.size() != fit.free_indices.size()) return worst;
  for (size_t k = 0; k < fit.free_indices.size(); ++k) {
    const int i = fit.free_indices[k];
    const ParameterSpec& spec = problem.parameters().specs()[i];
    if (!std::isfinite(fit.standard_errors[k])) {
      if (worst_width < std::numeric_limits<double>::infinity()) {
        worst_width = std::numeric_limits<double>::infinity();
        worst = {i, fmt::format("in the near-null space of the Jacobian (condition number {:.3g})",
                                fit.condition_number)};
      }
      continue;
    }
    const double width = (fit.upper_95[k] - fit.lower_95[k]) / (spec.upper - spec.lower);
    if (width >= worst_width && fit.lower_95[k] <= spec.lower && fit.upper_95[k] >= spec.upper) {
      worst_width = width;
      worst = {i, fmt::format("its 95 % interval [{:.4g}, {:.4g}] spans the whole bound range "
                              "[{:.4g}, {:.4g}]",
                              fit.lower_95[k], fit.upper_95[k], spec.lower, spec.upper)};
    }
  }
  return worst;
}

namespace {

// The profile of a parameter fixed as undetermined whose least cost lies
// below the fit's by more than the 95 % threshold in D (the data reject
// its fixed value), with its point of least cost; nullptr when none does.
std::pair<const ParameterProfile*, const ProfilePoint*> RejectedFixedValue(const ProfileSet& set,
                                                                           double fit_cost) {
  std::pair<const ParameterProfile*, const ProfilePoint*> worst = {nullptr, nullptr};
  double worst_statistic = set.threshold;
  for (const ParameterProfile& profile : set.profiles) {
    if (profile.fitted) continue;
    for (const ProfilePoint& point : profile.points) {
      if (!std::isfinite(point.cost) || point.values.empty()) continue;
      const double statistic = 2.0 * (fit_cost - point.cost) / set.residual_variance;
      if (statistic > worst_statistic) {
        worst_statistic = statistic;
        worst = {&profile, &point};
      }
    }
  }
  return worst;
}

}  // namespace

void ProfileTheKeptFit(const CalibrationConfig& config, const std::vector<bool>& undetermined,
                       bool compare_fits, CalibrationRun* run) {
  std::vector<int> also;
  for (size_t i = 0; i < undetermined.size(); ++i) {
    if (undetermined[i]) also.push_back(static_cast<int>(i));
  }
  RefittedProfiles profiled =
      ProfileAndRefit(*run->problem, *run->kept_fit(), also, config.ceres, config.profiles);
  run->profiles = std::move(profiled.profiles);
  run->restarts.insert(run->restarts.end(), profiled.restarts.begin(), profiled.restarts.end());
  if (profiled.restarts.empty() || !profiled.restarts.front().kept) return;
  // A profile found a better minimum: its refit (Ceres) replaces the kept
  // fit, named apart where that was another fitter's (the record keeps one
  // group per fitter name).
  if (run->fits[run->kept].summary.fitter != profiled.fit.summary.fitter) {
    profiled.fit.summary.fitter += "_refit";
  }
  run->fits[run->kept] = std::move(profiled.fit);
  if (compare_fits && run->fits.size() == 2) {
    run->agreement_in_standard_errors =
        FitAgreementInStandardErrors(run->fits[0], run->fits[1], &run->agreement_not_compared);
  }
}

void FreeRejectedFixedValues(const CalibrationConfig& config,
                             const std::vector<StateDataset>& datasets,
                             const std::vector<PathDataset>& paths, ModelParameters* parameters,
                             std::vector<bool>* undetermined, CalibrationRun* run) {
  for (int round = 0; round < kMaxUndeterminedRounds; ++round) {
    const FitResult* kept = run->kept_fit();
    const double fit_cost = kept->summary.final_cost;
    const auto [profile, point] = RejectedFixedValue(run->profiles, fit_cost);
    if (profile == nullptr) return;
    const int index = profile->parameter;
    ParameterSpec& spec = parameters->mutable_specs()[index];
    const double statistic = 2.0 * (fit_cost - point->cost) / run->profiles.residual_variance;
    const auto stays_fixed = [&](const std::string& why) {
      spec.free = false;
      run->freed.push_back(fmt::format(
          "{} stays fixed at {:.6g}: its profile rejects that value (D = {:.3g} at it, least "
          "cost at {:.6g}), but {}",
          spec.name, spec.value, statistic, point->value, why));
    };
    spec.free = true;
    std::unique_ptr<CalibrationProblem> problem;
    try {
      problem =
          std::make_unique<CalibrationProblem>(datasets, *parameters, config.predictor, paths);
    } catch (const InputError& refused) {
      stays_fixed(fmt::format("the problem refuses it free: {}", refused.what()));
      return;
    }
    std::vector<double> start;
    for (int i : problem->free_indices()) start.push_back(point->values[i]);
    FitResult refit;
    try {
      refit = CeresFitter(config.ceres).Fit(*problem, start);
    } catch (const std::exception&) {
      refit.summary.termination = FitTermination::kFailure;
    }
    if (!refit.summary.success() || !(refit.summary.final_cost < fit_cost)) {
      stays_fixed(refit.summary.success()
                      ? fmt::format("the refit with it free ended at a cost {:.6g} not below the "
                                    "fit's {:.6g}",
                                    refit.summary.final_cost, fit_cost)
                      : "the refit with it free failed: " + refit.summary.message);
      return;
    }
    (*undetermined)[index] = false;
    const std::string fixed = spec.name + " fixed at";
    run->undetermined.erase(std::remove_if(run->undetermined.begin(), run->undetermined.end(),
                                           [&](const std::string& u) {
                                             return u.compare(0, fixed.size(), fixed) == 0;
                                           }),
                            run->undetermined.end());
    run->freed.push_back(fmt::format(
        "{}: fixed at {:.6g} as undetermined at the search's optimum, but at the reported fit "
        "its profile rejects that value (D = {:.3g} at it, least cost at {:.6g}): freed and "
        "refitted from there (cost {:.6g} -> {:.6g}; the profiles below are of this fit)",
        spec.name, spec.value, statistic, point->value, fit_cost, refit.summary.final_cost));
    run->problem = std::move(problem);
    if (refit.summary.fitter != run->fits[run->kept].summary.fitter) {
      refit.summary.fitter += "_refit";
    }
    run->fits[run->kept] = std::move(refit);
    if (run->fits.size() == 2) {
      run->agreement_in_standard_errors = std::numeric_limits<double>::quiet_NaN();
      run->agreement_not_compared = fmt::format(
          "the other fit is of the problem with {} fixed, freed after the profiles", spec.name);
    }
    // The other fit (method both) is of the problem with the parameter fixed.
    ProfileTheKeptFit(config, *undetermined, /*compare_fits=*/false, run);
  }
}

}  // namespace granasym::calibration
