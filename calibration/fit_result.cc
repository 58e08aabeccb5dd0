// Covariance, intervals, correlation and warnings at the optimum.
#include "calibration/fit_result.h"

#include <fmt/format.h>

#include <Eigen/SVD>
#include <cmath>
#include <limits>

#include "common/error.h"

namespace granasym::calibration {

std::string FitSummary::Report() const {
  return fmt::format(
      "{}: {} after {} iterations, {} evaluations, cost {:.6g} -> {:.6g}, {:.3f} s{}", fitter,
      ToString(termination), iterations, evaluations, initial_cost, final_cost, wall_seconds,
      message.empty() ? "" : " (" + message + ")");
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

double StudentQuantile(double probability, int dof) {
  // Normal quantile by Acklam's rational approximation refined by one Halley step.
  const double p = probability;
  GRANASYM_CHECK(p > 0 && p < 1) << p;
  auto normal_quantile = [](double q) {
    static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02,
                               -2.759285104469687e+02, 1.383577518672690e+02,
                               -3.066479806614716e+01, 2.506628277459239e+00};
    static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02,
                               -1.556989798598866e+02, 6.680131188771972e+01,
                               -1.328068155288572e+01};
    static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01,
                               -2.400758277161838e+00, -2.549732539343734e+00,
                               4.374664141464968e+00,  2.938163982698783e+00};
    static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                               3.754408661907416e+00};
    double x;
    if (q < 0.02425) {
      const double t = std::sqrt(-2 * std::log(q));
      x = (((((c[0] * t + c[1]) * t + c[2]) * t + c[3]) * t + c[4]) * t + c[5]) /
          ((((d[0] * t + d[1]) * t + d[2]) * t + d[3]) * t + 1);
    } else if (q > 1 - 0.02425) {
      const double t = std::sqrt(-2 * std::log(1 - q));
      x = -(((((c[0] * t + c[1]) * t + c[2]) * t + c[3]) * t + c[4]) * t + c[5]) /
          ((((d[0] * t + d[1]) * t + d[2]) * t + d[3]) * t + 1);
    } else {
      const double t = q - 0.5, r = t * t;
      x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * t /
          (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
    }
    const double e = 0.5 * std::erfc(-x / std::sqrt(2.0)) - q;
    const double u = e * std::sqrt(2 * M_PI) * std::exp(x * x / 2);
    return x - u / (1 + x * u / 2);
  };
  const double z = normal_quantile(p);
  if (dof <= 0) return std::numeric_limits<double>::quiet_NaN();
  const double v = dof, z2 = z * z;
  return z + (z2 + 1) * z / (4 * v) + ((5 * z2 + 16) * z2 + 3) * z / (96 * v * v) +
         (((3 * z2 + 19) * z2 + 17) * z2 - 15) * z / (384 * v * v * v) +
         ((((79 * z2 + 776) * z2 + 1482) * z2 - 1920) * z2 - 945) * z / (92160 * v * v * v * v);
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
  for (int k = 0; k < n; ++k) {
    const ParameterSpec& spec = parameters.specs()[free[k]];
    const double band = options.bound_tolerance * (spec.upper - spec.lower);
    if (x[k] - spec.lower <= band) {
      result->warnings.push_back(fmt::format(
          "{} = {:.6g} is at its lower bound {}: the optimum may lie outside the bounds and its "
          "interval is not meaningful",
          spec.name, x[k], spec.lower));
    } else if (spec.upper - x[k] <= band) {
      result->warnings.push_back(fmt::format(
          "{} = {:.6g} is at its upper bound {}: the optimum may lie outside the bounds and its "
          "interval is not meaningful",
          spec.name, x[k], spec.upper));
    }
  }
}

}  // namespace granasym::calibration
