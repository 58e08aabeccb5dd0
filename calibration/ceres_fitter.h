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
    // Converged when stalled: the deviance D = 2 cost / s² (s² the residual
    // variance where the uncertainties are scaled by it, else 1) fell by
    // less than stall_deviance over the last stall_steps successful steps,
    // far below what a profile resolves (D < 3.84 for 95 %). A fit creeping
    // along a flat valley of the cost then ends where the creep starts, and
    // the profiles show what it leaves undetermined. 0: off.
    double stall_deviance = 0.01;
    int stall_steps = 10;
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

// Whether a solve has stalled (CeresFitter::Options::stall_deviance): fed
// the cost at the start and after each successful step, it answers true once
// the deviance fell by less than stall_deviance over the last stall_steps
// steps, and why() says so.
class StallDetector {
 public:
  StallDetector(const CeresFitter::Options& options, int degrees_of_freedom);
  bool Stalled(double cost);
  const std::string& why() const { return why_; }

 private:
  double stall_deviance_;
  int stall_steps_;
  bool scaled_;
  int degrees_of_freedom_;
  std::vector<double> costs_;
  std::string why_;
};

}  // namespace granasym::calibration
