// Ceres least squares on the calibration residuals.
#include "calibration/ceres_fitter.h"

#include <ceres/ceres.h>
#include <fmt/format.h>
#include <glog/logging.h>

#include <algorithm>
#include <chrono>
#include <mutex>

#include "common/error.h"

namespace granasym::calibration {

namespace {

// Ceres logs through glog; uninitialised, glog prints a warning about that
// and Ceres's own "Terminating: ..." lines on stderr. Every solve's
// termination and message are reported by the fit itself (summary.txt,
// warnings.txt), so glog is initialised once and keeps only fatal errors.
void QuietCeresLogging() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (!google::IsGoogleLoggingInitialized()) google::InitGoogleLogging("granasym");
    FLAGS_minloglevel = google::GLOG_FATAL;
  });
}

struct ResidualFunctor {
  const CalibrationProblem* problem;
  bool operator()(double const* const* parameters, double* residuals) const {
    std::string why;
    return problem->Residuals(parameters[0], residuals, &why);
  }
};

class HistoryCallback : public ceres::IterationCallback {
 public:
  HistoryCallback(const CalibrationProblem& problem, std::vector<HistoryPoint>* history)
      : problem_(problem), history_(history) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    const double best =
        history_->empty() ? summary.cost : std::min(summary.cost, history_->back().cost);
    history_->push_back({problem_.evaluations(), best, "ceres"});
    return ceres::SOLVER_CONTINUE;
  }

 private:
  const CalibrationProblem& problem_;
  std::vector<HistoryPoint>* history_;
};

// Ends a solve as converged when it has stalled (Options::stall_deviance).
class StallCallback : public ceres::IterationCallback {
 public:
  explicit StallCallback(StallDetector* detector) : detector_(detector) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    if (summary.iteration > 0 && !summary.step_is_successful) return ceres::SOLVER_CONTINUE;
    return detector_->Stalled(summary.cost) ? ceres::SOLVER_TERMINATE_SUCCESSFULLY
                                            : ceres::SOLVER_CONTINUE;
  }

 private:
  StallDetector* detector_;
};

}  // namespace

StallDetector::StallDetector(const CeresFitter::Options& options, int degrees_of_freedom)
    : stall_deviance_(options.stall_deviance),
      stall_steps_(options.stall_steps),
      scaled_(options.uncertainty.scale_by_residual_variance),
      degrees_of_freedom_(std::max(1, degrees_of_freedom)) {}

bool StallDetector::Stalled(double cost) {
  costs_.push_back(cost);
  if (stall_deviance_ <= 0 || static_cast<int>(costs_.size()) <= stall_steps_) return false;
  const double variance = scaled_ ? 2.0 * cost / degrees_of_freedom_ : 1.0;
  const double before = costs_[costs_.size() - 1 - static_cast<size_t>(stall_steps_)];
  const double fall = 2.0 * (before - cost) / variance;
  if (!(variance > 0) || !(fall < stall_deviance_)) return false;
  why_ = fmt::format(
      "Stalled: the deviance 2 cost/s^2 fell by {:.3g} over the last {} successful steps (< "
      "{:g}), far below what a profile resolves",
      fall, stall_steps_, stall_deviance_);
  return true;
}

bool CeresFitter::Options::IsValid(std::string* why) const {
  if (max_iterations < 1) {
    *why = fmt::format("max_iterations = {} must be >= 1", max_iterations);
    return false;
  }
  if (!(function_tolerance > 0 && parameter_tolerance > 0 && gradient_tolerance > 0)) {
    *why = "function_tolerance, parameter_tolerance and gradient_tolerance must be > 0";
    return false;
  }
  if (!(stall_deviance >= 0) || stall_steps < 1) {
    *why = fmt::format("stall_deviance = {} must be >= 0 and stall_steps = {} >= 1", stall_deviance,
                       stall_steps);
    return false;
  }
  if (!(relative_step > 0 && relative_step < 1e-2)) {
    *why = fmt::format("relative_step = {} must be in (0, 1e-2)", relative_step);
    return false;
  }
  return uncertainty.IsValid(why);
}

CeresFitter::Options CeresFitter::CostRefitOptions(const Options& options, bool fast) {
  Options refit = options;
  refit.compute_uncertainty = false;
  if (fast) {
    refit.forward_differences = true;
    refit.function_tolerance = std::max(refit.function_tolerance, kFastRefitTolerance);
  }
  return refit;
}

CeresFitter::CeresFitter(const Options& options) : options_(options) {
  std::string why;
  GRANASYM_CHECK(options_.IsValid(&why)) << why;
}

FitResult CeresFitter::Fit(const CalibrationProblem& problem,
                           const std::vector<double>& start) const {
  const auto t0 = std::chrono::steady_clock::now();
  const long evaluations0 = problem.evaluations();
  std::vector<double> x = start.empty() ? problem.FreeStart() : start;
  GRANASYM_CHECK(static_cast<int>(x.size()) == problem.num_free()) << x.size();
  const std::vector<double> lower = problem.FreeLower(), upper = problem.FreeUpper();
  for (size_t k = 0; k < x.size(); ++k) x[k] = std::min(std::max(x[k], lower[k]), upper[k]);

  FitResult result;
  result.summary.fitter = "ceres";
  result.summary.initial_cost = problem.Cost(x);
  if (!std::isfinite(result.summary.initial_cost)) {
    result.summary.termination = FitTermination::kFailure;
    std::string why;
    std::vector<double> r(static_cast<size_t>(problem.num_residuals()));
    problem.Residuals(x.data(), r.data(), &why);
    result.summary.message = "the model is undefined at the starting values: " + why;
    result.values = problem.parameters().WithFree(x);
    return result;
  }

  ceres::NumericDiffOptions numeric;
  numeric.relative_step_size = options_.relative_step;
  ceres::DynamicCostFunction* cost = nullptr;
  if (options_.forward_differences) {
    auto* forward = new ceres::DynamicNumericDiffCostFunction<ResidualFunctor, ceres::FORWARD>(
        new ResidualFunctor{&problem}, ceres::TAKE_OWNERSHIP, numeric);
    cost = forward;
  } else {
    cost = new ceres::DynamicNumericDiffCostFunction<ResidualFunctor, ceres::CENTRAL>(
        new ResidualFunctor{&problem}, ceres::TAKE_OWNERSHIP, numeric);
  }
  cost->AddParameterBlock(problem.num_free());
  cost->SetNumResiduals(problem.num_residuals());
  ceres::Problem ceres_problem;
  ceres_problem.AddResidualBlock(cost, nullptr, x.data());
  for (int k = 0; k < problem.num_free(); ++k) {
    ceres_problem.SetParameterLowerBound(x.data(), k, lower[k]);
    ceres_problem.SetParameterUpperBound(x.data(), k, upper[k]);
  }
  QuietCeresLogging();
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = options_.max_iterations;
  solver.function_tolerance = options_.function_tolerance;
  solver.parameter_tolerance = options_.parameter_tolerance;
  solver.gradient_tolerance = options_.gradient_tolerance;
  solver.num_threads = 1;
  solver.logging_type = ceres::SILENT;
  HistoryCallback callback(problem, &result.history);
  solver.callbacks.push_back(&callback);
  StallDetector detector(options_, problem.num_residuals() - problem.num_free());
  StallCallback stall(&detector);
  solver.callbacks.push_back(&stall);
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &ceres_problem, &summary);

  result.values = problem.parameters().WithFree(x);
  result.summary.iterations = static_cast<int>(summary.iterations.size());
  result.summary.final_cost = summary.final_cost;
  result.summary.message = detector.why().empty() ? summary.message : detector.why();
  switch (summary.termination_type) {
    case ceres::CONVERGENCE:
    case ceres::USER_SUCCESS:
      result.summary.termination = FitTermination::kConverged;
      break;
    case ceres::NO_CONVERGENCE:
      result.summary.termination = FitTermination::kNoConvergence;
      break;
    default:
      result.summary.termination = FitTermination::kFailure;
  }
  if (options_.compute_uncertainty && result.summary.termination != FitTermination::kFailure) {
    ComputeUncertainty(problem, options_.uncertainty, &result);
  }
  result.summary.evaluations = problem.evaluations() - evaluations0;
  result.summary.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace granasym::calibration
