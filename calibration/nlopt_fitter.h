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

namespace granasym::calibration {

enum class GlobalAlgorithm { kCrs2, kIsres, kDirectL, kMlsl };
const char* ToString(GlobalAlgorithm algorithm);
bool FromString(const std::string& name, GlobalAlgorithm* algorithm);

enum class LocalPolish { kNone, kBobyqa, kCeres };
const char* ToString(LocalPolish polish);
bool FromString(const std::string& name, LocalPolish* polish);

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
    CeresFitter::Options ceres;  // used when polish = kCeres
    UncertaintyOptions uncertainty;
    bool IsValid(std::string* why) const;
  };

  explicit NloptFitter(const Options& options);
  FitResult Fit(const CalibrationProblem& problem) const;

 private:
  Options options_;
};

}  // namespace granasym::calibration
