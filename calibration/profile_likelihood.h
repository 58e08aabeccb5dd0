// Profile-likelihood intervals of a fit (issue 36 §3): each profiled
// parameter is fixed on a grid around its optimum, the other free parameters
// re-optimised (Ceres, warm-started from the neighbouring grid point), and
// the cost recorded. The statistic
//
//   D(θ) = 2 (cost(θ) − cost_min) / s²
//
// (s² the fit's residual variance, 1 when the uncertainties are true standard
// deviations; cost_min the fit's cost, or the profile's own least cost where
// lower: ParameterProfile::reference_cost) is compared with the 95 % threshold of one parameter:
// t²_{0.975, m−n} (= F_{1, m−n; 0.95}) with the residual-variance estimate,
// χ²_{1; 0.95} = 3.84 without; for a model linear in its parameters the
// profile interval is then exactly the Jacobian (Wald) interval of
// fit_result.h. The 95 % interval runs between the crossings of the
// threshold (linear interpolation between grid points).
//
// Grid: on ln θ for positive scale parameters (ProfiledOnLogScale: a lower
// bound > 0 and bounds spanning two decades or more, e.g. λ*, κ*, r, h_s, α,
// β), on θ otherwise. Each side has points_per_side points out to 2·√threshold
// standard errors (where the fit reports one), else out to a decade (log
// scale) or the bound; a side that has not crossed the threshold at its last
// point is extended by doubling steps up to a decade or the bound. A side
// ends where the statistic passes 4 × threshold, or where the model is
// undefined (an ordering constraint such as e_d0 < e_c0): a step that fails
// is bisected six times towards the last good point, so the side ends within
// 1/64 of that step from the domain's edge, or crosses the threshold before
// it.
//
// A parameter is `flat` (not determined) when its profile stays below the
// threshold up to a bound of the fit, up to where the model is undefined or
// the refit fails, or over a decade (log scale: the range below the
// threshold spans a factor of 10): flat_low..flat_high is the range it stays
// below the threshold over.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "calibration/calibration_problem.h"
#include "calibration/ceres_fitter.h"
#include "calibration/fit_result.h"
#include "common/enum_names.h"

namespace granasym::calibration {

// How one side of a profile ends.
enum class ProfileEnd { kCrossed, kBound, kDecade, kDomain };

}  // namespace granasym::calibration

namespace granasym {
template <>
struct EnumNames<calibration::ProfileEnd> {
  using E = calibration::ProfileEnd;
  static constexpr EnumEntry<E> kEntries[] = {
      {E::kCrossed, "crossed", "the statistic crosses the 95 % threshold"},
      {E::kBound, "bound", "below the threshold up to the bound of the fit"},
      {E::kDecade, "decade", "below the threshold over a decade"},
      {E::kDomain, "domain",
       "below the threshold up to where the model is undefined or the refit fails"},
  };
};
}  // namespace granasym

namespace granasym::calibration {

struct ProfileOptions {
  bool enabled = true;
  int points_per_side = 8;       // grid: 2 × points_per_side + 1 with the optimum
  int max_extension_points = 4;  // doubling steps per side beyond the grid
  // Threads over the profiled parameters; 0: one per parameter, at most the
  // hardware's. The profiles do not depend on it.
  int threads = 0;
  // Refits from a profile's point of least cost (ProfileAndRefit): at most
  // this many, each when that cost lies below the fit's by more than
  // restart_drop × threshold in D (the profile_lower_cost warning's margin).
  int max_restarts = 3;
  double restart_drop = 0.1;
  // Refits by CeresFitter::CostRefitOptions(ceres, fast_refits): forward
  // differences and a function tolerance of 1e-8 (about half the
  // evaluations; intervals within 1e-3 of their width of the exact refits'
  // in the tests).
  bool fast_refits = true;
  bool IsValid(std::string* why) const;
};

struct ProfilePoint {
  double value = 0.0;          // the profiled parameter
  double cost = 0.0;           // ½ Σ r² with the others re-optimised; +∞ when the refit failed
  double statistic = 0.0;      // D (see above); +∞ when the refit failed
  bool converged = false;      // the refit converged (the optimum: the fit's own)
  long evaluations = 0;        // the refit's residual-vector evaluations
  std::vector<double> values;  // the full parameter vector there
};

struct ParameterProfile {
  int parameter = -1;  // model_parameters.h order
  std::string name, units;
  bool log_scale = false;
  // Free in the fit; false: fixed by RunCalibration as undetermined (profiled
  // from its fixed value).
  bool fitted = true;
  double optimum = 0.0;
  std::vector<ProfilePoint> points;  // ascending in value, the optimum included
  ProfileEnd lower_end = ProfileEnd::kCrossed, upper_end = ProfileEnd::kCrossed;
  // The 95 % interval's ends where crossed, else NaN.
  double lower = std::numeric_limits<double>::quiet_NaN();
  double upper = std::numeric_limits<double>::quiet_NaN();
  // The lowest and highest values whose statistic stays below the threshold.
  double flat_low = 0.0, flat_high = 0.0;
  // cost_min of D: the fit's cost, or this profile's least cost where lower
  // (a fitted parameter's: the fit missed the optimum, a warning; an
  // undetermined one's: the data prefer another value, not significantly
  // when the profile is flat).
  double reference_cost = 0.0;
  double least_value = 0.0;  // where the profile's cost is least
  int refits = 0;
  long evaluations = 0;  // residual-vector evaluations of its refits
  double wall_seconds = 0.0;
  std::string failure;  // why the last refit of a kDomain side failed

  bool flat() const;
  // "lambda_star: [0.0201, 0.0219] (17 points)" or "r: flat from 0.01 (bound)
  // to 3 (bound): not determined".
  std::string Text() const;
};

struct ProfileSet {
  std::vector<ParameterProfile> profiles;
  double fit_cost = 0.0;  // the profiled fit's cost
  double residual_variance = 1.0;
  double threshold = 0.0;
  std::string statistic;  // how D and the threshold were computed, in words
  int threads = 1;
  double wall_seconds = 0.0;
  std::vector<std::string> warnings;
  bool empty() const { return profiles.empty(); }
};

// Whether `spec` is profiled on ln θ: lower bound > 0 and upper ≥ 100 lower.
bool ProfiledOnLogScale(const ParameterSpec& spec);

// The profiles of every free parameter of `fit` (a successful fit of
// `problem`) and of the parameters `also` (model_parameters.h indices of
// parameters fixed in `problem`, e.g. those RunCalibration fixed as
// undetermined: profiled from their fixed value with the free ones
// re-optimised). `ceres` are the refits' options.
ProfileSet ProfileLikelihood(const CalibrationProblem& problem, const FitResult& fit,
                             const std::vector<int>& also, const CeresFitter::Options& ceres,
                             const ProfileOptions& options);

// A refit of the whole problem from the point of least cost of a fitted
// parameter's profile, where that cost lies below the fit's: the fit ended
// in a local minimum (or stopped short of the optimum), and the profile,
// moving one parameter at a time with the others refitted, found a better
// basin.
struct ProfileRestart {
  std::string parameter;      // whose profile found the lower cost
  double value = 0.0;         // its value at that point
  double profile_cost = 0.0;  // the profile's cost there
  double cost_before = 0.0;   // the fit's
  double cost_after = 0.0;    // the refit's; +∞ when it failed
  bool kept = false;          // the refit succeeded with a lower cost and replaced the fit
  // "refitted from the kappa_star profile (kappa_star = 0.0101): cost 5976.16 -> 645.03".
  std::string Text() const;
};

struct RefittedProfiles {
  FitResult fit;  // the fit the profiles belong to: the given one or its last kept refit
  ProfileSet profiles;
  std::vector<ProfileRestart> restarts;
};

// ProfileLikelihood, then, while a fitted parameter's profile reaches a cost
// below the fit's by more than options.restart_drop × threshold in D (and at
// most options.max_restarts times), a full Ceres refit (`ceres`) from the
// profile point of least cost over all profiles; a refit with a lower cost
// replaces the fit and the profiles are recomputed from it. A refit that does
// not lower the cost ends the restarts (recorded, not kept; the profiles'
// profile_lower_cost warning stays).
RefittedProfiles ProfileAndRefit(const CalibrationProblem& problem, const FitResult& fit,
                                 const std::vector<int>& also, const CeresFitter::Options& ceres,
                                 const ProfileOptions& options);

// profiles.csv: parameter,value,cost,statistic,threshold,converged,log_scale,
// optimum,ci95_low,ci95_high,flat — one row per grid point, by parameter.
std::string ProfilesCsv(const ProfileSet& set);
// profile_parameters.csv, one row per profile for the figure
// (plots/calibration_profiles.gp): parameter,log_scale,optimum,threshold,
// flat,low,high,low_crossed,high_crossed — low and high the interval's ends
// where the profile crosses the threshold, else the ends of its flat range.
std::string ProfileParametersCsv(const ProfileSet& set);
// The summary's section: the statistic, then one line per parameter.
std::string ProfilesText(const ProfileSet& set);

}  // namespace granasym::calibration
