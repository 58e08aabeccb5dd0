// Small statistics shared by the study tables and the calibration: the
// Student-t quantile of confidence intervals, means and the least-squares line.
#pragma once

#include <limits>
#include <vector>

namespace granasym {

// Two-sided Student-t quantile t_{p, dof} (Cornish-Fisher expansion of the
// normal quantile; exact to about 1e-3 relative for dof >= 3); NaN for dof <= 0.
double StudentQuantile(double probability, int degrees_of_freedom);

// t_{0.975, dof}, the factor of a 95 % interval of a mean: tabulated for
// dof 1-4 (where the expansion is least accurate), StudentQuantile beyond.
double StudentT95(int degrees_of_freedom);

// The mean (NaN when empty) and the standard error of the mean (NaN below two values).
double Mean(const std::vector<double>& v);
double StandardError(const std::vector<double>& v);

// Ordinary least squares y = intercept + slope x with standard errors (NaN
// with fewer than 2 distinct x; the errors need 3 points).
struct LineFit {
  double slope = std::numeric_limits<double>::quiet_NaN();
  double intercept = std::numeric_limits<double>::quiet_NaN();
  double slope_error = std::numeric_limits<double>::quiet_NaN();
  double intercept_error = std::numeric_limits<double>::quiet_NaN();
  int points = 0;
  bool valid() const { return slope == slope; }
  double At(double x) const { return intercept + slope * x; }
};
LineFit FitLine(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace granasym
