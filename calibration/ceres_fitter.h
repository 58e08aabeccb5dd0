// Bounded nonlinear least squares with Ceres (Levenberg–Marquardt, dense QR)
// on the weighted residuals of a CalibrationProblem; derivatives by central
// differences of the (analytic or integrated) asymptotes.
#pragma once

#include <string>
#include <vector>

#include "calibration/calibration_problem.h"
#include "calibration/fit_result.h"

namespace granasym::calibration {

class CeresFitter {
 public:
  struct Options {
    int max_iterations = 200;
    double function_tolerance = 1e-12;   // relative change of the cost
    double parameter_tolerance = 1e-12;  // relative step
    double gradient_tolerance = 1e-14;
    // Central-difference step, relative to the parameter value.
    double relative_step = 1e-6;
    // Forward differences instead of central ones: half the residual
    // evaluations per Jacobian (n + 1 instead of 2n), an O(step) error in the
    // Jacobian; for refits that need only the cost (profiles, Pareto sweep),
    // where the step moves the optimum's cost by far less than the
    // tolerances they are compared at.
    bool forward_differences = false;
    UncertaintyOptions uncertainty;
    // The covariance, intervals and residuals at the optimum
    // (ComputeUncertainty); false for refits that need only the cost
    // (profile_likelihood.h, pareto.h).
    bool compute_uncertainty = true;
    bool IsValid(std::string* why) const;
  };

  // The options of refits that need only the cost (profiles, the Pareto
  // sweep): no uncertainty; with `fast`, forward differences and a function
  // tolerance of at least kFastRefitTolerance (the refit's cost within about
  // that fraction of its optimum: a profile's D within ~1e-8 × the number of
  // residuals, far below its threshold of about 4).
  static constexpr double kFastRefitTolerance = 1e-8;
  static Options CostRefitOptions(const Options& options, bool fast);

  explicit CeresFitter(const Options& options);
  // Starts from `start` (free values; empty: the parameters' starting values).
  FitResult Fit(const CalibrationProblem& problem, const std::vector<double>& start = {}) const;

 private:
  Options options_;
};

}  // namespace granasym::calibration
