#include "common/statistics.h"

#include <cmath>

#include "common/error.h"

namespace granasym {

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

double StudentT95(int dof) {
  static const double table[] = {12.706, 4.303, 3.182, 2.776};
  if (dof < 1) return std::numeric_limits<double>::quiet_NaN();
  if (dof <= 4) return table[dof - 1];
  return StudentQuantile(0.975, dof);
}

double Mean(const std::vector<double>& v) {
  double sum = 0;
  for (double x : v) sum += x;
  return v.empty() ? std::nan("") : sum / static_cast<double>(v.size());
}

double StandardError(const std::vector<double>& v) {
  if (v.size() < 2) return std::nan("");
  const double m = Mean(v);
  double ss = 0;
  for (double x : v) ss += (x - m) * (x - m);
  return std::sqrt(ss / static_cast<double>(v.size() - 1) / static_cast<double>(v.size()));
}

LineFit FitLine(const std::vector<double>& x, const std::vector<double>& y) {
  LineFit fit;
  fit.points = static_cast<int>(x.size());
  const double n = static_cast<double>(x.size());
  if (x.size() < 2) return fit;
  double mx = 0, my = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    mx += x[i] / n;
    my += y[i] / n;
  }
  double sxx = 0, sxy = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
  }
  if (!(sxx > 0)) return fit;
  fit.slope = sxy / sxx;
  fit.intercept = my - fit.slope * mx;
  if (x.size() > 2) {
    double ss = 0;
    for (size_t i = 0; i < x.size(); ++i) {
      const double r = y[i] - fit.intercept - fit.slope * x[i];
      ss += r * r;
    }
    const double s2 = ss / (n - 2);
    fit.slope_error = std::sqrt(s2 / sxx);
    fit.intercept_error = std::sqrt(s2 * (1.0 / n + mx * mx / sxx));
  }
  return fit;
}

}  // namespace granasym
