// The small statistics of the analyses: a mean or a fitted value with its
// 95 % Student-t interval (`Estimate`), two estimates compared by Welch's
// interval of their difference (`Compare`), and the verdict of a list of
// such comparisons (`VerdictOf`). Pure functions of numbers: no file I/O.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "common/enum_names.h"

namespace granasym::analysis {

enum class Agreement { kAgree, kDiffer, kUndetermined };
}  // namespace granasym::analysis

template <>
struct granasym::EnumNames<granasym::analysis::Agreement> {
  static constexpr EnumEntry<analysis::Agreement> kEntries[] = {
      {analysis::Agreement::kAgree, "agree", "the difference is inside its 95 % interval"},
      {analysis::Agreement::kDiffer, "differ", "the difference is outside its 95 % interval"},
      {analysis::Agreement::kUndetermined, "undetermined",
       "an estimate lacks its interval (fewer than two states, or three points for a line)"},
  };
};

namespace granasym::analysis {

// A mean (or a fitted value) with its standard error and the half-width of
// its two-sided 95 % interval (Student t with `dof` degrees of freedom);
// NaN errors when there is no interval.
struct Estimate {
  double mean = std::numeric_limits<double>::quiet_NaN();
  double standard_error = std::numeric_limits<double>::quiet_NaN();
  double half_width = std::numeric_limits<double>::quiet_NaN();
  int n = 0;    // values
  int dof = 0;  // degrees of freedom of the interval (0: none)
  bool has_interval() const { return dof >= 1 && std::isfinite(standard_error); }
  static Estimate Of(const std::vector<double>& values);  // mean over n, dof n − 1
  static Estimate Fitted(double value, double standard_error, int points);  // dof points − 2
};

// Whether two estimates agree: the difference b − a against the half-width
// of its 95 % interval, t_{ν} sqrt(se_a² + se_b²), ν by Welch–Satterthwaite
// (rounded down, so the interval is not narrower than it should be).
struct Comparison {
  Agreement agreement = Agreement::kUndetermined;
  double difference = std::numeric_limits<double>::quiet_NaN();
  double half_width = std::numeric_limits<double>::quiet_NaN();
};
Comparison Compare(const Estimate& a, const Estimate& b);

// The verdict of named comparisons: "<subject>_dependent" when one differs
// (`reason` names each that does), "<subject>_independent" when all agree,
// else "undetermined" (`reason`: the `missing` texts, what lacks an interval).
std::string VerdictOf(const std::vector<std::pair<const char*, const Comparison*>>& comparisons,
                      const std::vector<std::string>& missing, std::string* reason,
                      const std::string& subject = "rate");

// The mean with its interval of one member over the finite values of `used`.
template <typename State>
Estimate MeanOver(const std::vector<const State*>& used, double State::*member) {
  std::vector<double> values;
  for (const State* s : used) {
    if (std::isfinite(s->*member)) values.push_back(s->*member);
  }
  return Estimate::Of(values);
}

}  // namespace granasym::analysis
