// The outcome of a fit: parameters, their uncertainty from the linearised
// model at the optimum, residuals, warnings and the objective history.
//
// Covariance: C = s² (JᵀJ)⁻¹ with J the Jacobian of the weighted residuals
// with respect to the free parameters (central differences) and, when
// scale_by_residual_variance, s² = 2 cost/(m − n) (the data uncertainties are
// then relative weights); otherwise s² = 1 (they are true standard deviations).
// (JᵀJ)⁻¹ comes from the SVD of J; singular values below
// singular_tolerance·σ_max are dropped and reported as a near-singular
// covariance with the parameters of the poorly determined direction, and
// kept as null_directions (the summary then names them instead of printing
// correlations, which would describe the pseudo-inverse).
// 95 % intervals: value ± t_{0.975, m−n} · standard error.
// A standard error and interval are reported (FitResult::Reported) only where
// both mean something: the parameter is in no near-null direction of J and
// not at a bound of the fit (there the optimum may lie beyond the bound and
// the linearisation describes the bound, not the data).
#pragma once

#include <string>
#include <vector>

#include "calibration/calibration_problem.h"
#include "common/enum_names.h"
#include "constitutive/eigen.h"

namespace granasym::calibration {

enum class FitTermination { kConverged, kNoConvergence, kFailure };

}  // namespace granasym::calibration

namespace granasym {
template <>
struct EnumNames<calibration::FitTermination> {
  using T = calibration::FitTermination;
  static constexpr EnumEntry<T> kEntries[] = {
      {T::kConverged, "converged", "a convergence criterion was met"},
      {T::kNoConvergence, "no_convergence", "stopped before a convergence criterion was met"},
      {T::kFailure, "failure", "the fit failed (see the message)"},
  };
};
}  // namespace granasym

namespace granasym::calibration {

// The name-table functions (common/enum_names.h) for this namespace's enums.
using granasym::FromString;
using granasym::ToString;

struct FitSummary {
  std::string fitter;  // "ceres", "nlopt:crs2+bobyqa", ...
  FitTermination termination = FitTermination::kFailure;
  std::string message;
  int iterations = 0;
  long evaluations = 0;       // residual-vector evaluations
  double initial_cost = 0.0;  // ½ Σ r² of the weighted residuals
  double final_cost = 0.0;
  double wall_seconds = 0.0;
  bool success() const { return termination != FitTermination::kFailure; }
  std::string Report() const;  // one line
};

struct HistoryPoint {
  long evaluation = 0;  // residual evaluations so far
  double cost = 0.0;    // best cost so far
  std::string stage;    // "ceres", "global start 2", "polish"
};

struct UncertaintyOptions {
  bool scale_by_residual_variance = true;
  // Relative singular-value threshold of J below which a direction counts as
  // not determined.
  double singular_tolerance = 1e-8;
  // A parameter within this fraction of its bound range (or of the bound's
  // own magnitude, when smaller) counts as at the bound (AtBound).
  double bound_tolerance = 1e-4;
  // Relative central-difference step for J (of max(|θ|, 1e-3 · bound range)).
  double difference_step = 1e-5;
  bool IsValid(std::string* why) const;
};

// A direction of the free parameters that the data do not determine: a right
// singular vector of the scaled Jacobian (columns per relative change of each
// parameter) whose singular value is below singular_tolerance · σ_max.
struct NullDirection {
  double singular_ratio = 0.0;     // σ/σ_max
  std::vector<double> components;  // free order, unit length, relative changes
  // "0.71 lambda_star - 0.70 n_intercept" (components above 0.05 in size).
  std::string Text(const ModelParameters& parameters, const std::vector<int>& free) const;
};

struct FitResult {
  FitSummary summary;
  std::vector<double> values;  // full parameter vector (model_parameters.h order)
  std::vector<int> free_indices;
  Eigen::MatrixXd covariance;   // free × free, in the parameters' units
  Eigen::MatrixXd correlation;  // free × free; meaningful when null_directions is empty
  std::vector<NullDirection> null_directions;  // of the Jacobian; empty: full rank
  std::vector<double> standard_errors;         // free order; NaN when not determined
  std::vector<double> lower_95, upper_95;
  std::vector<bool> at_bound;      // free order: ended at a bound of the fit (AtBound)
  double residual_variance = 1.0;  // s²
  int degrees_of_freedom = 0;      // m − n
  double condition_number = 0.0;   // σ_max/σ_min of J (scaled columns)
  std::vector<std::string> warnings;
  std::vector<HistoryPoint> history;
  std::vector<PointResidual> residuals;

  // Whether free parameter k (free order) has a standard error and interval
  // worth reporting: finite and not at a bound.
  bool Reported(size_t k) const;
};

// Whether `value` lies at a bound of `spec` within `tolerance`: within
// tolerance · min(upper − lower, |bound|) of it (|bound| for a nonzero bound,
// so that a parameter whose bounds span decades, h_s in [1e2, 1e9] kPa, is
// not at its lower bound at 7e4). −1 lower, +1 upper, 0 neither.
int AtBound(const ParameterSpec& spec, double value, double tolerance);

// Fills the uncertainty fields, residuals and warnings of `result` at
// result->values (which must hold a valid full parameter vector).
void ComputeUncertainty(const CalibrationProblem& problem, const UncertaintyOptions& options,
                        FitResult* result);

}  // namespace granasym::calibration
