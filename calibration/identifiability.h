// Which parameters the data determine (issue 36 §3): the search's test of
// a fit (LeastDetermined) and, after the profiles, the freeing of a parameter
// fixed as undetermined whose profile rejects its fixed value.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "calibration/calibration_report.h"

namespace granasym::calibration {

// At most this many parameters are fixed as undetermined.
constexpr int kMaxUndeterminedRounds = 5;

// The free parameter that `fit` determines least, if the data do not
// determine it: in the near-null space of the Jacobian first, else the one
// whose 95 % interval spans most of (and at least) its bound range; index −1
// when every free parameter is determined. The reason in words.
std::pair<int, std::string> LeastDetermined(const CalibrationProblem& problem,
                                            const FitResult& fit);

// The profiles of the kept fit and of the parameters `undetermined` marks
// (ProfileAndRefit), into run->profiles; its restarts are appended to
// run->restarts, and a kept restart replaces the kept fit (named
// "<fitter>_refit" where it was another fitter's), the two fits compared
// again with `compare_fits`.
void ProfileTheKeptFit(const CalibrationConfig& config, const std::vector<bool>& undetermined,
                       bool compare_fits, CalibrationRun* run);

// RunCalibration's step after the profiles: the search for undetermined
// parameters judges each at its probe's optimum, and a profile's refit may
// move the fit to another basin where a parameter fixed there is determined
// after all. Where the profile of a parameter in `*undetermined` (fixed in
// `*parameters` and `run->problem`) rejects its fixed value at the kept fit
// (D above the 95 % threshold), it is freed, the problem refitted from the
// profile's point of least cost and profiled again (ProfileAndRefit), up to
// five times; run->freed says what happened (a parameter whose refit does not
// lower the cost stays fixed, said so). Needs run->profiles of the kept fit.
void FreeRejectedFixedValues(const CalibrationConfig& config,
                             const std::vector<StateDataset>& datasets,
                             const std::vector<PathDataset>& paths, ModelParameters* parameters,
                             std::vector<bool>* undetermined, CalibrationRun* run);

}  // namespace granasym::calibration
