// NLopt global search and polish.
#include "calibration/nlopt_fitter.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <nlopt.hpp>
#include <random>

#include "common/error.h"

namespace granasym::calibration {

namespace {

// Objective value for parameters outside the model's domain: finite, so that
// the derivative-free algorithms keep working, and far above any real cost.
constexpr double kPenalty = 1e20;

struct Objective {
  const CalibrationProblem* problem;
  std::vector<double> lower, upper;
  std::vector<HistoryPoint>* history;
  std::string stage;
  double best = std::numeric_limits<double>::infinity();

  std::vector<double> ToParameters(const double* u) const {
    std::vector<double> x(lower.size());
    for (size_t k = 0; k < x.size(); ++k) x[k] = lower[k] + u[k] * (upper[k] - lower[k]);
    return x;
  }
  std::vector<double> ToUnit(const std::vector<double>& x) const {
    std::vector<double> u(x.size());
    for (size_t k = 0; k < x.size(); ++k) {
      u[k] = std::min(1.0, std::max(0.0, (x[k] - lower[k]) / (upper[k] - lower[k])));
    }
    return u;
  }
  double operator()(const double* u) {
    double cost = problem->Cost(ToParameters(u));
    if (!std::isfinite(cost)) cost = kPenalty;
    if (cost < best) {
      best = cost;
      history->push_back({problem->evaluations(), best, stage});
    }
    return cost;
  }
};

double NloptObjective(unsigned, const double* u, double* gradient, void* data) {
  GRANASYM_CHECK(gradient == nullptr) << "derivative-free algorithms only";
  return (*static_cast<Objective*>(data))(u);
}

nlopt::algorithm ToNlopt(GlobalAlgorithm algorithm) {
  switch (algorithm) {
    case GlobalAlgorithm::kCrs2:
      return nlopt::GN_CRS2_LM;
    case GlobalAlgorithm::kIsres:
      return nlopt::GN_ISRES;
    case GlobalAlgorithm::kDirectL:
      return nlopt::GN_DIRECT_L;
    case GlobalAlgorithm::kMlsl:
      return nlopt::GN_MLSL_LDS;
  }
  return nlopt::GN_CRS2_LM;
}

// Runs one NLopt optimisation; NLopt's exceptions become a message.
bool RunNlopt(nlopt::opt& opt, std::vector<double>* u, double* value, std::string* message) {
  try {
    const nlopt::result code = opt.optimize(*u, *value);
    *message = fmt::format("nlopt result {}", static_cast<int>(code));
    return code > 0;
  } catch (const nlopt::roundoff_limited&) {
    *message = "nlopt: roundoff limited (the result is usable)";
    return true;
  } catch (const std::exception& error) {
    *message =
        fmt::format("nlopt::opt::optimize ({}) failed: {}", opt.get_algorithm_name(), error.what());
    return false;
  }
}

}  // namespace

bool NloptFitter::Options::IsValid(std::string* why) const {
  if (starts < 1 || starts > 1000) {
    *why = fmt::format("starts = {} must be in [1, 1000]", starts);
    return false;
  }
  if (max_evaluations < 10) {
    *why = fmt::format("max_evaluations = {} must be >= 10", max_evaluations);
    return false;
  }
  if (polish_max_evaluations < 10) {
    *why = fmt::format("polish_max_evaluations = {} must be >= 10", polish_max_evaluations);
    return false;
  }
  if (!(polish_relative_tolerance > 0 && polish_relative_tolerance < 1e-2)) {
    *why = fmt::format("polish_relative_tolerance = {} must be in (0, 1e-2)",
                       polish_relative_tolerance);
    return false;
  }
  return ceres.IsValid(why) && uncertainty.IsValid(why);
}

NloptFitter::NloptFitter(const Options& options) : options_(options) {
  std::string why;
  GRANASYM_CHECK(options_.IsValid(&why)) << why;
}

FitResult NloptFitter::Fit(const CalibrationProblem& problem) const {
  const auto t0 = std::chrono::steady_clock::now();
  const long evaluations0 = problem.evaluations();
  const unsigned n = static_cast<unsigned>(problem.num_free());
  FitResult result;
  result.summary.fitter =
      fmt::format("nlopt:{}+{}", ToString(options_.algorithm), ToString(options_.polish));
  Objective objective{&problem, problem.FreeLower(), problem.FreeUpper(), &result.history, ""};
  const std::vector<double> start = problem.FreeStart();
  result.summary.initial_cost = problem.Cost(start);

  std::mt19937_64 random(options_.seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<double> best_u = objective.ToUnit(start);
  double best_value = std::numeric_limits<double>::infinity();
  std::string messages;
  int iterations = 0;
  for (int s = 0; s < options_.starts; ++s) {
    std::vector<double> u = objective.ToUnit(start);
    if (s > 0) {
      for (double& value : u) value = uniform(random);
    }
    nlopt::srand(options_.seed + static_cast<unsigned long>(s));
    nlopt::opt opt(ToNlopt(options_.algorithm), n);
    opt.set_lower_bounds(std::vector<double>(n, 0.0));
    opt.set_upper_bounds(std::vector<double>(n, 1.0));
    objective.stage = fmt::format("global start {}", s + 1);
    opt.set_min_objective(NloptObjective, &objective);
    opt.set_maxeval(options_.max_evaluations);
    opt.set_xtol_rel(1e-10);
    if (options_.algorithm == GlobalAlgorithm::kMlsl) {
      nlopt::opt local(nlopt::LN_BOBYQA, n);
      local.set_xtol_rel(1e-8);
      local.set_maxeval(std::max(50, options_.max_evaluations / 10));
      opt.set_local_optimizer(local);
    }
    double value = kPenalty;
    std::string message;
    const bool ok = RunNlopt(opt, &u, &value, &message);
    ++iterations;
    if (!ok) messages += fmt::format("start {}: {}; ", s + 1, message);
    if (value < best_value) {
      best_value = value;
      best_u = u;
    }
  }
  if (!(best_value < kPenalty)) {
    result.summary.termination = FitTermination::kFailure;
    result.summary.message = "no valid parameters found by the global search; " + messages;
    result.values = problem.parameters().WithFree(objective.ToParameters(best_u.data()));
    result.summary.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return result;
  }
  result.summary.termination = FitTermination::kConverged;
  std::vector<double> x = objective.ToParameters(best_u.data());
  double final_cost = best_value;

  if (options_.polish == LocalPolish::kBobyqa) {
    nlopt::opt local(nlopt::LN_BOBYQA, n);
    local.set_lower_bounds(std::vector<double>(n, 0.0));
    local.set_upper_bounds(std::vector<double>(n, 1.0));
    objective.stage = "polish";
    local.set_min_objective(NloptObjective, &objective);
    local.set_maxeval(options_.polish_max_evaluations);
    local.set_xtol_rel(options_.polish_relative_tolerance);
    local.set_ftol_rel(1e-15);
    std::vector<double> u = best_u;
    double value = best_value;
    std::string message;
    const bool ok = RunNlopt(local, &u, &value, &message);
    ++iterations;
    if (ok && value <= best_value) {
      x = objective.ToParameters(u.data());
      final_cost = value;
    }
    if (!ok) {
      result.summary.termination = FitTermination::kNoConvergence;
      messages += "polish: " + message;
    }
    if (local.last_optimize_result() == nlopt::MAXEVAL_REACHED) {
      result.summary.termination = FitTermination::kNoConvergence;
      messages += "polish: BOBYQA reached polish_max_evaluations; ";
    }
  } else if (options_.polish == LocalPolish::kCeres) {
    const FitResult polished = CeresFitter(options_.ceres).Fit(problem, x);
    iterations += polished.summary.iterations;
    for (const HistoryPoint& h : polished.history) {
      result.history.push_back({h.evaluation, std::min(h.cost, final_cost), "polish"});
    }
    if (polished.summary.success() && polished.summary.final_cost <= final_cost) {
      for (size_t k = 0; k < x.size(); ++k) x[k] = polished.values[problem.free_indices()[k]];
      final_cost = polished.summary.final_cost;
    }
    if (!polished.summary.success()) messages += "ceres polish: " + polished.summary.message;
  }
  result.values = problem.parameters().WithFree(x);
  result.summary.final_cost = final_cost;
  result.summary.iterations = iterations;
  result.summary.message = messages;
  ComputeUncertainty(problem, options_.uncertainty, &result);
  result.summary.evaluations = problem.evaluations() - evaluations0;
  result.summary.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace granasym::calibration
