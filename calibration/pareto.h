// The trade-off between two groups of residuals (issue 36 §3): a Pareto
// front by a weighted-sum sweep.
//
// A ResidualGroups assigns each data point (dataset, point) to group 0, 1 or
// neither (−1); a point's residuals belong to its group, and the path
// residuals (fitted unloading branches and whole-path datasets:
// CalibrationProblem::Group(kPath)) to `path_group`. Two splits:
//  - AsymptoticPathGroups: every asymptotic state against every whole path —
//    the trade-off (asymptotic states and whole paths do not agree
//    perfectly for any of the models: the paper's point about the CSL's
//    position), chosen by ChooseResidualGroups whenever the problem has path
//    residuals;
//  - DefaultResidualGroups: the compression side — NCL, compression and ASBS
//    states — against the critical and extension states (CSL, extension),
//    the path residuals in neither group (kept at their weight): chosen when
//    there are no path residuals.
//
// The sweep minimises, for weights w of group 0,
//
//   w · C_0 + (1 − w) · C_1 (+ ½ C_other),   C_g = ½ Σ_{residuals of g} r²
//
// (the points' weights scaled by 2w and 2(1 − w), so w = ½ is the ordinary
// fit), at w/(1 − w) = 10^x for x evenly from −log10(max_weight_ratio) to
// +log10(max_weight_ratio) (an odd number of points: the middle one is the
// ordinary fit), each fit warm-started from its neighbour towards the ends.
// A weighted sum finds the convex part of the front only.
//
// Distinct points: neighbours (in weight) whose costs differ by at most
// merge_tolerance of each group's range on the front in both groups are one
// point of the front (a weighted sum returns the same fit over a range of
// weights where a bound holds or the front jumps); each point carries the
// index of its distinct point and that point's weight range. While the front
// has fewer than min_distinct distinct points, it is refined where it
// moves: the weights between the two neighbouring distinct points farthest
// apart (in normalised costs) are bisected in ln(w/(1 − w)) — two at a time,
// on two threads, each fit warm-started from the neighbour of lower weighted
// cost, so that the result does not depend on the threads — at most
// max_refinements fits, never closer than min_refine_decades.
//
// The compromise: the knee, the point closest to the utopia point (each
// group's least cost on the front) in costs normalised by their range on the
// front, f_g = (C_g − min C_g)/(max C_g − min C_g): it gives up equal
// fractions of what each group can gain, whatever the groups' sizes and
// units. When either cost changes by less than 1e-6 of itself over the
// front, the groups agree and the compromise is the ordinary fit.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "calibration/calibration_problem.h"
#include "calibration/ceres_fitter.h"
#include "calibration/fit_result.h"

namespace granasym::calibration {

struct ResidualGroups {
  std::array<std::string, 2> names;  // e.g. "ncl_compression", "csl_extension"
  std::array<std::string, 2> descriptions;
  // Per dataset and point: 0, 1 or −1 (neither: kept at its own weight).
  std::vector<std::vector<int>> point_group;
  // The group of the path residuals (unloading branches and whole paths):
  // 0, 1 or −1 (neither: kept at their own weight in every fit).
  int path_group = -1;
  // Which groups are traded and why, in words (the summary's line).
  std::string choice;
  // The number of weighted residuals of group g in `problem`.
  int Residuals(const CalibrationProblem& problem, int g) const;
};

// The default split (see above).
ResidualGroups DefaultResidualGroups(const CalibrationProblem& problem);
// Asymptotic states (group 0, "asymptotic_states") against whole paths
// (group 1, "whole_paths"); the problem must have path residuals.
ResidualGroups AsymptoticPathGroups(const CalibrationProblem& problem);
// AsymptoticPathGroups when the problem has path residuals, else
// DefaultResidualGroups; `choice` says which and why.
ResidualGroups ChooseResidualGroups(const CalibrationProblem& problem);

struct ParetoOptions {
  bool enabled = true;
  int points = 11;                // odd, >= 5
  double max_weight_ratio = 1e3;  // the ends' w/(1 − w) and its inverse
  // The sweep's fits by CeresFitter::CostRefitOptions(ceres, fast_refits).
  bool fast_refits = true;
  // Refinement (see above): the distinct points sought, the fits it may add,
  // the least step in log10(w/(1 − w)) it bisects, and the merging tolerance.
  int min_distinct = 10;
  int max_refinements = 12;
  double min_refine_decades = 0.01;
  double merge_tolerance = 1e-3;
  bool IsValid(std::string* why) const;
};

struct ParetoPoint {
  double weight = 0.5;                        // w of group 0
  std::array<double, 2> cost = {0, 0};        // C_g, unweighted by w
  std::array<double, 2> rms = {0, 0};         // √(2 C_g / m_g): RMS weighted residual
  std::array<double, 2> normalised = {0, 0};  // f_g (see above)
  std::vector<double> values;                 // full parameter vector
  bool converged = false;
  bool refined = false;  // added by the refinement, not on the uniform sweep
  // Its distinct point (ParetoFront::distinct) and that point's weights.
  int distinct = 0;
  double weight_low = 0.5, weight_high = 0.5;
  bool labelled = false;  // its label is drawn (labels kept apart on the figure)
  // "w = 0.2" or "w = 0.000999-0.2" (the distinct point's weight range).
  std::string Label() const;
};

struct ParetoFront {
  ResidualGroups groups;
  std::array<int, 2> residuals = {0, 0};  // m_g
  std::vector<ParetoPoint> points;        // ascending in weight
  int compromise = -1;                    // index into points
  int ordinary = -1;                      // w = ½
  bool trade_off = false;                 // false: the groups agree
  std::string rule;                       // the compromise rule and why, in words
  std::string not_computed;               // non-empty: why there is no front
  std::vector<std::string> warnings;
  double wall_seconds = 0.0;
  long evaluations = 0;    // residual-vector evaluations of the sweep's fits
  int distinct = 0;        // distinct points (see above)
  int refinements = 0;     // fits added by the refinement
  std::string refinement;  // how the refinement ended, in words ("" when none was needed)
  bool computed() const { return not_computed.empty() && !points.empty(); }
  // Whether C_0 does not increase and C_1 does not decrease with w (each
  // step within `tolerance` of the larger cost).
  bool Monotone(double tolerance) const;
};

// The front of `problem` (its kept fit `fit` is the start of the sweep);
// not_computed says why when a group has no residuals.
ParetoFront ComputeParetoFront(const CalibrationProblem& problem, const FitResult& fit,
                               const ResidualGroups& groups, const CeresFitter::Options& ceres,
                               const ParetoOptions& options);

// Sets each point's distinct index and weight range and the front's
// distinct count (merge_tolerance: see above), and which labels are drawn:
// one per distinct point, those of the ends, the ordinary fit and the
// compromise first, then any at least `label_spacing` (in RMS residuals
// normalised by their range) from every label drawn.
void MergeDistinctPoints(ParetoFront* front, double merge_tolerance, double label_spacing = 0.08);

// pareto.csv: weight,cost_<g0>,cost_<g1>,rms_<g0>,rms_<g1>,normalised_<g0>,
// normalised_<g1>,converged,compromise,ordinary,distinct,weight_low,
// weight_high,label,labelled,refined,group_0,group_1 (the groups' names on
// every row, for the figure), then the parameters.
std::string ParetoCsv(const ParetoFront& front, const ModelParameters& parameters);
// The summary's section.
std::string ParetoText(const ParetoFront& front, const ModelParameters& parameters);

}  // namespace granasym::calibration
