// Covariance, intervals, correlation and warnings at the optimum.
#include "calibration/fit_result.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "common/error.h"
#include "common/statistics.h"
#include "constitutive/eigen.h"

namespace granasym::calibration {

std::string FitSummary::Report() const {
  return fmt::format(
      "{}: {} after {} iterations, {} evaluations, cost {:.6g} -> {:.6g}, {:.3f} s{}", fitter,
      ToString(termination), iterations, evaluations, initial_cost, final_cost, wall_seconds,
      message.empty() ? "" : " (" + message + ")");
}

std::string NullDirection::Text(const ModelParameters& parameters,
                                const std::vector<int>& free) const {
  // The sign of the largest component positive, so that the text is stable.
  double largest = 0;
  for (double c : components) largest = std::abs(c) > std::abs(largest) ? c : largest;
  const double sign = largest < 0 ? -1.0 : 1.0;
  std::string text;
  for (size_t k = 0; k < components.size() && k < free.size(); ++k) {
    const double c = sign * components[k];
    if (std::abs(c) < 0.05) continue;
    text += text.empty() ? fmt::format("{:.2f} {}", c, parameters.specs()[free[k]].name)
                         : fmt::format(" {} {:.2f} {}", c < 0 ? "-" : "+", std::abs(c),
                                       parameters.specs()[free[k]].name);
  }
  return text;
}

bool FitResult::Reported(size_t k) const {
  return k < standard_errors.size() && std::isfinite(standard_errors[k]) &&
         !(k < at_bound.size() && at_bound[k]);
}

int AtBound(const ParameterSpec& spec, double value, double tolerance) {
  const double range = spec.upper - spec.lower;
  const auto band = [&](double bound) {
    return tolerance * (bound != 0 ? std::min(range, std::abs(bound)) : range);
  };
  if (value - spec.lower <= band(spec.lower)) return -1;
  if (spec.upper - value <= band(spec.upper)) return 1;
  return 0;
}

bool UncertaintyOptions::IsValid(std::string* why) const {
  if (!(singular_tolerance > 0 && singular_tolerance < 1)) {
    *why = fmt::format("singular_tolerance = {} must be in (0, 1)", singular_tolerance);
    return false;
  }
  if (!(bound_tolerance >= 0 && bound_tolerance < 0.5)) {
    *why = fmt::format("bound_tolerance = {} must be in [0, 0.5)", bound_tolerance);
    return false;
  }
  if (!(difference_step > 0 && difference_step < 0.1)) {
    *why = fmt::format("difference_step = {} must be in (0, 0.1)", difference_step);
    return false;
  }
  return true;
}

void ComputeUncertainty(const CalibrationProblem& problem, const UncertaintyOptions& options,
                        FitResult* result) {
  std::string why;
  GRANASYM_CHECK(options.IsValid(&why)) << why;
  const ModelParameters& parameters = problem.parameters();
  const std::vector<int>& free = problem.free_indices();
  const int n = problem.num_free(), m = problem.num_residuals();
  result->free_indices = free;
  const double nan = std::numeric_limits<double>::quiet_NaN();

  if (!problem.Evaluate(result->values, &result->residuals, &why)) {
    result->warnings.push_back("cannot evaluate the residuals at the result: " + why);
    return;
  }
  int clamped = 0;
  for (const PointResidual& r : result->residuals) clamped += r.clamped ? 1 : 0;
  if (clamped > 0) {
    result->warnings.push_back(fmt::format(
        "{} states have a psi_epsilon outside the model's asymptote range (the range end is "
        "used)",
        clamped));
  }

  std::vector<double> x(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) x[k] = result->values[free[k]];
  Eigen::VectorXd r0(m);
  if (!problem.Residuals(x.data(), r0.data(), &why)) {
    result->warnings.push_back("cannot evaluate the residuals at the result: " + why);
    return;
  }
  const double cost = 0.5 * r0.squaredNorm();
  result->degrees_of_freedom = m - n;
  result->residual_variance =
      options.scale_by_residual_variance ? 2.0 * cost / std::max(1, m - n) : 1.0;

  // Jacobian by central differences (one-sided where a side is invalid).
  Eigen::MatrixXd jacobian(m, n);
  for (int k = 0; k < n; ++k) {
    const ParameterSpec& spec = parameters.specs()[free[k]];
    const double h =
        options.difference_step * std::max(std::abs(x[k]), 1e-3 * (spec.upper - spec.lower));
    std::vector<double> plus = x, minus = x;
    plus[k] += h;
    minus[k] -= h;
    Eigen::VectorXd rp(m), rm(m);
    const bool ok_plus = problem.Residuals(plus.data(), rp.data(), &why);
    const bool ok_minus = problem.Residuals(minus.data(), rm.data(), &why);
    if (ok_plus && ok_minus) {
      jacobian.col(k) = (rp - rm) / (2 * h);
    } else if (ok_plus) {
      jacobian.col(k) = (rp - r0) / h;
    } else if (ok_minus) {
      jacobian.col(k) = (r0 - rm) / h;
    } else {
      result->warnings.push_back(
          fmt::format("{}: the model is undefined on both sides of the result ({}); no uncertainty",
                      spec.name, why));
      jacobian.col(k).setZero();
    }
  }
  // Columns per relative change of each parameter, so that the conditioning
  // reflects the data and not the units (a column of numerical noise stays small).
  Eigen::VectorXd scale(n);
  for (int k = 0; k < n; ++k) {
    const ParameterSpec& spec = parameters.specs()[free[k]];
    scale[k] = std::max(std::abs(x[k]), 1e-3 * (spec.upper - spec.lower));
  }
  const Eigen::MatrixXd scaled = jacobian * scale.asDiagonal();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(scaled, Eigen::ComputeThinV);
  const Eigen::VectorXd sv = svd.singularValues();
  const double smax = sv.size() > 0 ? sv[0] : 0.0;
  result->condition_number = sv.size() > 0 && sv[sv.size() - 1] > 0
                                 ? smax / sv[sv.size() - 1]
                                 : std::numeric_limits<double>::infinity();
  Eigen::MatrixXd inverse = Eigen::MatrixXd::Zero(n, n);
  std::vector<bool> undetermined(static_cast<size_t>(n), false);
  for (int i = 0; i < sv.size(); ++i) {
    const Eigen::VectorXd v = svd.matrixV().col(i);
    if (sv[i] > options.singular_tolerance * smax && sv[i] > 0) {
      inverse += v * v.transpose() / (sv[i] * sv[i]);
    } else {
      NullDirection null;
      null.singular_ratio = smax > 0 ? sv[i] / smax : 0.0;
      for (int k = 0; k < n; ++k) null.components.push_back(v[k]);
      result->null_directions.push_back(null);
      std::string names;
      for (int k = 0; k < n; ++k) {
        if (std::abs(v[k]) > 0.3) {
          undetermined[k] = true;
          names += (names.empty() ? "" : ", ") + parameters.specs()[free[k]].name;
        }
      }
      result->warnings.push_back(fmt::format(
          "near-singular covariance (singular value ratio {:.3g}): the data do not determine "
          "{}; their standard errors are not reported",
          smax > 0 ? sv[i] / smax : 0.0, names));
    }
  }
  if (std::isfinite(result->condition_number) && result->condition_number > 1e6 &&
      result->condition_number <= 1.0 / options.singular_tolerance) {
    result->warnings.push_back(fmt::format(
        "ill-conditioned Jacobian (condition number {:.3g}): strongly correlated parameters",
        result->condition_number));
  }
  result->covariance =
      result->residual_variance * scale.asDiagonal() * inverse * scale.asDiagonal();
  result->correlation = Eigen::MatrixXd::Identity(n, n);
  result->standard_errors.assign(static_cast<size_t>(n), nan);
  result->lower_95.assign(static_cast<size_t>(n), nan);
  result->upper_95.assign(static_cast<size_t>(n), nan);
  const double t =
      result->degrees_of_freedom > 0 ? StudentQuantile(0.975, result->degrees_of_freedom) : nan;
  for (int k = 0; k < n; ++k) {
    if (undetermined[k]) continue;
    const double se = std::sqrt(std::max(0.0, result->covariance(k, k)));
    result->standard_errors[k] = se;
    result->lower_95[k] = x[k] - t * se;
    result->upper_95[k] = x[k] + t * se;
  }
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double d = std::sqrt(result->covariance(i, i) * result->covariance(j, j));
      result->correlation(i, j) = d > 0 ? result->covariance(i, j) / d : (i == j ? 1.0 : nan);
    }
  }
  result->at_bound.assign(static_cast<size_t>(n), false);
  for (int k = 0; k < n; ++k) {
    const ParameterSpec& spec = parameters.specs()[free[k]];
    const int side = AtBound(spec, x[k], options.bound_tolerance);
    if (side == 0) continue;
    result->at_bound[k] = true;
    result->warnings.push_back(fmt::format(
        "{} = {:.6g} is at its {} bound {}: the optimum may lie outside the bounds, so its "
        "standard error and interval are not reported",
        spec.name, x[k], side < 0 ? "lower" : "upper", side < 0 ? spec.lower : spec.upper));
  }
}

}  // namespace granasym::calibration
