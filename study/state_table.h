// The table of asymptotic states across all cases of a study folder:
// DIR/asymptotic_states.csv and .h5 (one row per detector-carrying stage of
// every case, and one per case without a result, so that nothing is silently
// missing; one per detector-carrying stage with two replicates or more for
// their ensemble-mean path, source `ensemble`, study/ensemble_path.h),
// DIR/asymptotic_states_summary.csv (mean and 95 % confidence interval over
// the replicates' rows, beside the ensemble row's state), DIR/ncl_fit.csv
// (the study's own NCLs that OCR and p_e* refer to: a state uses the NCL of
// its nearest ancestor case that has one, else the study's `ncl`; replicate
// 0 is the NCL through the ensemble rows), and DIR/path_convergence.csv (the
// paper's Sec. 4.3 evidence: where paths of one ψ_ε from different starting
// states join, per replicate).
// The analyses of the table (the rate study, figures, calibration, report)
// are the analysis library's (analysis/).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "study/state_table_names.h"

namespace granasym::study {

// One asymptotic state (or the reason there is none).
struct StateRow {
  std::string case_id, case_name, run, stage, figures;
  int replicate = 1;  // 0 for an ensemble row
  TableSource source = TableSource::kReplicate;
  TableKind kind = TableKind::kNone;
  TableStatus status = TableStatus::kNoResult;
  std::string detector;
  std::string flags;  // validity flags, ';'-separated
  std::string message;
  std::string ncl_reference;  // the case whose NCL gives OCR and p_e* (empty: none)
  double psi_epsilon_deg = 0, p_kpa = 0, e = 0, ln_1_plus_e = 0, psi_sigma_deg = 0, q_over_p = 0,
         ocr = 0, p_e_star_kpa = 0, inertial_number_dmin = 0, inertial_number_dmax = 0,
         coordination = 0, mechanical_coordination = 0, max_relative_overlap = 0;
  // The detector's window and measures (AsymptoteRecord).
  double window_strain = 0, window_lnp = 0, psi_change_deg = 0, slope_change = 0, lnp_change = 0,
         dln1pe_dlnp = 0;
  // The range of p over the detector's window (kPa), and whether the state
  // is an extension window that held before the path left the valid range
  // or drifted (1) rather than the stage's last window (0).
  double window_p_min_kpa = 0, window_p_max_kpa = 0;
  int held_before_end = 0;
};

// The isotropic NCL ln(1+e) = N − λ* ln(p / 1 kPa) of one replicate and one
// case with ψ_ε = 0° stages (the study's NCL, or one of a sample with another
// material or time step), fitted through its stage-end states that are not a gas
// and have overlaps below 10 % (detected or drifting: on a ψ_ε = 0° path the
// detector's tests are at the noise level of a small sample). Replicate 0:
// the NCL through the ensemble rows, which they refer to.
struct NclFit {
  int replicate = 1;
  std::string case_name;
  int points = 0;
  int detected = 0, drifting = 0;  // the states' detector statuses
  double n = 0, lambda = 0;        // N and λ*
  double p_min_kpa = 0, p_max_kpa = 0;
  bool valid() const { return points >= 2 && lambda > 0; }
};

// Where paths of one ψ_ε from different starting states join.
struct ConvergenceRow {
  int replicate = 1;
  TableKind kind = TableKind::kCompression;  // compression or extension
  double psi_epsilon_deg = 0;
  std::string case_a, case_b;
  std::string status;  // joined, not_joined, no_overlap
  double joined_at_p_kpa = 0, ln_1_plus_e = 0, psi_sigma_deg = 0;
  double overlap_from_p_kpa = 0, overlap_to_p_kpa = 0;
};

// Tolerances of the convergence check, in (ln(1+e), ψ_σ) at a common ln p.
struct ConvergenceTolerance {
  // Paths of one sample from different starts keep ψ_σ apart by 1–2° for
  // a long way at a few thousand spheres, while ln(1+e) agrees within 0.005.
  double ln_1_plus_e = 0.005;
  double psi_sigma_deg = 2.0;
  int grid_points = 40;
  // Each path is averaged over ±this in ln p at a grid point (a sample of a
  // few thousand spheres fluctuates by about ±1° in ψ_σ from row to row).
  double smoothing_lnp = 0.1;
  // Extension paths are compared at a common ln(1+e) (JoinExtensionPaths):
  // at the paper's rate they end in dense flows whose p barely moves while
  // ln(1+e) rises at the imposed rate, so ln p is no axis for them. Along the
  // paper's extension paths at 3000 spheres ln p scatters by 0.13-0.19 about
  // its trend; averaged over ±0.005 of ln(1+e) (about 0.03 of strain at
  // ψ_ε = 100°, 15 rows) that is about 0.08 with the rows' correlation.
  double ln_p = 0.25;
  double smoothing_ln_1_plus_e = 0.005;
};

// A path as samples ascending in x, with y and ψ_σ (deg): x = ln p and
// y = ln(1+e) for compression (JoinPaths), x = ln(1+e) and y = ln p for
// extension (JoinExtensionPaths).
struct PathSamples {
  std::vector<double> x, y, psi;
};
// Where two compression paths of one ψ_ε join: the first point of a grid
// over their common ln p range, in the direction of rising p, from which both
// ln(1+e) and ψ_σ stay within the tolerances to the end; joined only if they
// stay together over at least a quarter of the common range.
ConvergenceRow JoinPaths(const PathSamples& a, const PathSamples& b,
                         const ConvergenceTolerance& tolerance);
// The same for two extension paths over their common ln(1+e) range (which
// the imposed dilation makes monotone), in the direction of rising ln(1+e),
// with ln p and ψ_σ within the tolerances; the overlap's p is the paths' mean
// at its ends.
ConvergenceRow JoinExtensionPaths(const PathSamples& a, const PathSamples& b,
                                  const ConvergenceTolerance& tolerance);

struct StateTableSummary {
  std::string directory;
  std::map<std::string, std::map<std::string, int>> counts;           // kind → status → rows
  std::map<std::string, std::map<std::string, int>> ensemble_counts;  // of the ensemble rows
  std::vector<NclFit> ncl;
  int joined = 0, not_joined = 0;
  std::string Text() const;
};

// Mean and half-width of the two-sided 95 % confidence interval of the mean
// (Student t with n − 1 degrees of freedom); NaN half-width below 2 values.
struct Interval {
  double mean, half_width;
};
Interval MeanInterval95(const std::vector<double>& values);

// y at `at` of samples ascending in x: the mean of the samples within ±h
// (the fluctuations of a small sample smoothed), or linear interpolation
// where none is that close (h = 0: interpolation).
double Smoothed(const std::vector<double>& x, const std::vector<double>& y, double at, double h);

// A field of the study's CSV files (quoted when it holds a comma, a quote or a
// line break; line breaks become spaces) and a number (10 significant
// digits; empty for NaN).
std::string CsvText(const std::string& text);
std::string CsvNumber(double value);

// One column of the table as its files hold it (the Python module's
// DataFrame): the name, the units of a number column ("" for text and
// integer columns), and per row the number (numbers and integers) or the
// text (text columns and the enumerations' names).
struct StateTableColumn {
  std::string name, units;
  bool text = false;
  bool integer = false;  // a number column of integers (replicate, held_before_end)
  std::vector<double> numbers;
  std::vector<std::string> texts;
};
// The columns of `rows` in the order of the CSV file, from the one table of
// columns that the writers and the reader use.
std::vector<StateTableColumn> StateTableColumns(const std::vector<StateRow>& rows);

// Builds the tables from the case folders below `directory` and writes them.
StateTableSummary WriteStateTable(const std::string& directory,
                                  const ConvergenceTolerance& tolerance = {});

// Reads the rows back from DIR/asymptotic_states.h5.
std::vector<StateRow> ReadStateTable(const std::string& directory);
// The rows without the ensemble rows: what an analysis that aggregates over
// replicates reads (an ensemble row is no replicate of its state).
std::vector<StateRow> WithoutEnsembleRows(std::vector<StateRow> rows);

}  // namespace granasym::study
