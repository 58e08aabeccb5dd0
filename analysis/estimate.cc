#include "analysis/estimate.h"

#include <fmt/format.h>

#include <algorithm>

#include "common/statistics.h"

namespace granasym::analysis {

Estimate Estimate::Of(const std::vector<double>& values) {
  Estimate estimate;
  estimate.n = static_cast<int>(values.size());
  if (values.empty()) return estimate;
  double sum = 0;
  for (double v : values) sum += v;
  estimate.mean = sum / static_cast<double>(values.size());
  if (values.size() < 2) return estimate;
  double squares = 0;
  for (double v : values) squares += (v - estimate.mean) * (v - estimate.mean);
  const double variance = squares / static_cast<double>(values.size() - 1);
  estimate.dof = estimate.n - 1;
  estimate.standard_error = std::sqrt(variance / static_cast<double>(values.size()));
  estimate.half_width = StudentT95(estimate.dof) * estimate.standard_error;
  return estimate;
}

Estimate Estimate::Fitted(double value, double standard_error, int points) {
  Estimate estimate;
  estimate.mean = value;
  estimate.n = points;
  if (points >= 3 && std::isfinite(standard_error)) {
    estimate.dof = points - 2;
    estimate.standard_error = standard_error;
    estimate.half_width = StudentT95(estimate.dof) * standard_error;
  }
  return estimate;
}

Comparison Compare(const Estimate& a, const Estimate& b) {
  Comparison c;
  c.difference = b.mean - a.mean;
  if (!std::isfinite(c.difference) || !a.has_interval() || !b.has_interval()) return c;
  const double va = a.standard_error * a.standard_error, vb = b.standard_error * b.standard_error;
  const double denominator = va * va / a.dof + vb * vb / b.dof;
  double dof = denominator > 0 ? (va + vb) * (va + vb) / denominator : a.dof + b.dof;
  dof = std::max(1.0, std::floor(dof));
  c.half_width = StudentT95(static_cast<int>(std::min(dof, 1e6))) * std::sqrt(va + vb);
  c.agreement = std::abs(c.difference) <= c.half_width ? Agreement::kAgree : Agreement::kDiffer;
  return c;
}

std::string VerdictOf(const std::vector<std::pair<const char*, const Comparison*>>& comparisons,
                      const std::vector<std::string>& missing, std::string* reason,
                      const std::string& subject) {
  bool differs = false, agree = true;
  std::vector<std::string> reasons;
  for (const auto& [name, c] : comparisons) {
    agree = agree && c->agreement == Agreement::kAgree;
    if (c->agreement == Agreement::kDiffer) {
      differs = true;
      reasons.push_back(fmt::format("{} differs by {:.4g} (95 % interval +-{:.2g})", name,
                                    c->difference, c->half_width));
    }
  }
  if (!differs && !agree) reasons = missing;
  for (const std::string& r : reasons) *reason += (reason->empty() ? "" : "; ") + r;
  return differs ? subject + "_dependent" : agree ? subject + "_independent" : "undetermined";
}

}  // namespace granasym::analysis
