// Global search with NLopt followed by a local polish (issue 4 §3).
//
// The search runs in the unit cube of the free parameters' bounds (so that
// CRS2/ISRES/DIRECT-L/MLSL see comparable scales) on the same objective as
// Ceres, ½ Σ r² of the weighted residuals; invalid parameter combinations
// (e.g. κ* ≥ λ*) get a large finite penalty. `starts` independent searches
// (the first from the starting values, the others from uniform random points,
// each with its own NLopt seed) keep the best; the polish is BOBYQA or Ceres
// from there, and the uncertainty is that of the polished optimum.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "calibration/calibration_problem.h"
#include "calibration/ceres_fitter.h"
#include "calibration/fit_result.h"
#include "common/enum_names.h"

namespace granasym::calibration {

enum class GlobalAlgorithm { kCrs2, kIsres, kDirectL, kMlsl };
enum class LocalPolish { kNone, kBobyqa, kCeres };

}  // namespace granasym::calibration

namespace granasym {
template <>
struct EnumNames<calibration::GlobalAlgorithm> {
  using A = calibration::GlobalAlgorithm;
  static constexpr EnumEntry<A> kEntries[] = {
      {A::kCrs2, "crs2", "controlled random search with local mutation"},
      {A::kIsres, "isres", "improved stochastic ranking evolution strategy"},
      {A::kDirectL, "direct_l", "locally biased DIRECT"},
      {A::kMlsl, "mlsl", "multi-level single-linkage, low-discrepancy starts"},
  };
};
template <>
struct EnumNames<calibration::LocalPolish> {
  using P = calibration::LocalPolish;
  static constexpr EnumEntry<P> kEntries[] = {
      {P::kNone, "none", "no local polish"},
      {P::kBobyqa, "bobyqa", "NLopt BOBYQA"},
      {P::kCeres, "ceres", "Ceres from the best global point"},
  };
};
}  // namespace granasym

namespace granasym::calibration {

// The name-table functions (common/enum_names.h) for this namespace's enums.
using granasym::FromString;
using granasym::ToString;

class NloptFitter {
 public:
  struct Options {
    GlobalAlgorithm algorithm = GlobalAlgorithm::kCrs2;
    int starts = 3;  // independent global searches
    // Objective evaluations per global search; CRS2 needs a few hundred per
    // free parameter to settle its population.
    int max_evaluations = 1500;
    uint64_t seed = 1;  // NLopt's random seed of the first start (start k: seed + k)
    LocalPolish polish = LocalPolish::kBobyqa;
    int polish_max_evaluations = 4000;
    double polish_relative_tolerance = 1e-12;  // BOBYQA xtol_rel in the unit cube
    CeresFitter::Options ceres;                // used when polish = kCeres
    UncertaintyOptions uncertainty;
    bool IsValid(std::string* why) const;
  };

  explicit NloptFitter(const Options& options);
  FitResult Fit(const CalibrationProblem& problem) const;

 private:
  Options options_;
};

}  // namespace granasym::calibration
