#include "study/state_table.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <type_traits>
#include <variant>

#include "common/config.h"
#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/statistics.h"
#include "common/text_file.h"
#include "common/time_series.h"
#include "dem/run_record.h"
#include "dem/run_record_names.h"
#include "dem/stage_validity.h"
#include "study/case_record.h"
#include "study/ensemble_path.h"
#include "study/state_table_names.h"
#include "study/study_folder.h"

namespace granasym::study {
namespace fs = std::filesystem;
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The kind of an asymptotic state, as the table names it.
TableKind KindOf(dem::PathKind path, double psi_epsilon_deg) {
  switch (path) {
    case dem::PathKind::kIsochoric:
      return TableKind::kCsl;
    case dem::PathKind::kCompression:
      return std::abs(psi_epsilon_deg) < 1e-6 ? TableKind::kNcl : TableKind::kCompression;
    case dem::PathKind::kExtension:
      return TableKind::kExtension;
    case dem::PathKind::kStressControlled:
      return TableKind::kTriaxial;
  }
  GRANASYM_CHECK(false) << "unknown path kind";
  return TableKind::kNone;
}

TableStatus StatusOf(dem::AsymptoteStatus status) {
  switch (status) {
    case dem::AsymptoteStatus::kDetected:
      return TableStatus::kDetected;
    case dem::AsymptoteStatus::kDrifting:
      return TableStatus::kDrifting;
    case dem::AsymptoteStatus::kNotReached:
      return TableStatus::kNotReached;
    case dem::AsymptoteStatus::kGas:
      return TableStatus::kGas;
    case dem::AsymptoteStatus::kInvalid:
      return TableStatus::kInvalid;
  }
  GRANASYM_CHECK(false) << "unknown asymptote status";
  return TableStatus::kNoResult;
}

struct CaseFolder {
  CaseRecord record;
  bool finished = false;  // done.toml for the current key, and a result
  std::string termination, message;
};

std::vector<CaseFolder> ListCases(const std::string& directory) {
  std::vector<CaseFolder> cases;
  for (const CaseRecord& record : ReadCaseRecords(directory)) {
    const fs::path folder(record.directory);
    CaseFolder c;
    c.record = record;
    const CaseDone outcome = record.Done();
    if (outcome.done) {
      c.termination = ToString(outcome.done->termination);
      c.message = outcome.done->message;
      c.finished = outcome.finished;
      // A partial result under the final name is not the case's result.
      if (!outcome.mismatch.empty()) c.message = outcome.mismatch;
    }
    if (!c.finished && c.message.empty()) {
      c.message = !fs::exists(folder) ? "not run (no case folder: was its shard run?)"
                  : fs::exists(folder / "result.h5.ckpt") ? "interrupted: resumes on the next run"
                                                          : "not run";
    }
    cases.push_back(std::move(c));
  }
  return cases;
}

// Which tests of the criterion failed at the stage end.
std::string DriftReason(const dem::AsymptoteRecord& a) {
  const dem::AsymptoteCriterion& c = a.criterion;
  std::vector<std::string> failed;
  auto check = [&failed](double value, double tolerance, const char* what) {
    if (!(value < tolerance))
      failed.push_back(fmt::format("{} {:.3g} (< {:g})", what, value, tolerance));
  };
  check(a.psi_change_deg, c.psi_tolerance_deg, "psi_sigma changed by deg");
  switch (a.path_kind) {
    case dem::PathKind::kIsochoric:
      check(a.lnp_change, c.lnp_tolerance, "ln p changed by");
      break;
    case dem::PathKind::kCompression:
      check(a.slope_change, c.slope_tolerance, "d ln(1+e)/d ln p changed by a fraction");
      break;
    case dem::PathKind::kExtension:
      check(a.lnp_half_difference, c.lnp_tolerance, "the rate of ln p changed by");
      break;
    case dem::PathKind::kStressControlled:
      check(a.psi_epsilon_change_deg, c.psi_epsilon_tolerance_deg, "psi_epsilon changed by deg");
      check(a.lnv_change, c.lnv_tolerance, "ln(1+e) changed by");
      break;
  }
  std::string text = "still drifting:";
  for (const std::string& f : failed) text += " " + f + ";";
  if (!text.empty() && text.back() == ';') text.pop_back();
  return text;
}

// A row with the case's fields set.
StateRow CaseFields(const CaseRecord& record) {
  StateRow row;
  row.case_id = record.id;
  row.case_name = record.name;
  row.run = record.run;
  row.figures = record.figures.Text();
  row.replicate = record.replicate;
  return row;
}

// The row of a stage record (a replicate's, or an ensemble's mean path's),
// on a row with the case's fields set.
StateRow RowFrom(StateRow row, const dem::StageRecord& stage) {
  const dem::AsymptoteRecord& a = *stage.asymptote;
  row.stage = stage.name;
  row.kind = KindOf(a.path_kind, a.psi_epsilon_deg);
  row.status = StatusOf(a.status);
  row.detector = stage.asymptote_criterion;
  for (dem::ValidityFlag flag : stage.validity.flags) {
    row.flags += std::string(row.flags.empty() ? "" : ";") + ToString(flag);
  }
  row.message = stage.stop_reason;
  if (a.status == dem::AsymptoteStatus::kDrifting)
    row.message = DriftReason(a) + "; " + row.message;
  row.psi_epsilon_deg = a.psi_epsilon_deg;
  row.p_kpa = a.mean_stress_kpa;
  row.e = a.void_ratio;
  row.ln_1_plus_e = std::log1p(a.void_ratio);
  row.psi_sigma_deg = a.psi_sigma_deg;
  row.q_over_p = a.q_over_p;
  row.inertial_number_dmin = a.inertial_number_dmin;
  row.inertial_number_dmax = a.inertial_number_dmax;
  row.coordination = a.coordination;
  row.mechanical_coordination = a.mechanical_coordination;
  row.max_relative_overlap = a.max_relative_overlap;
  row.window_strain = a.window_strain;
  row.window_lnp = a.window_lnp;
  row.psi_change_deg = a.psi_change_deg;
  row.slope_change = a.slope_change;
  row.lnp_change = a.lnp_change;
  row.dln1pe_dlnp = a.dln1pe_dlnp;
  row.window_p_min_kpa = a.window_strain > 0 ? a.p_min_kpa : kNaN;
  row.window_p_max_kpa = a.window_strain > 0 ? a.p_max_kpa : kNaN;
  row.held_before_end = a.before_end ? 1 : 0;
  row.ocr = kNaN;
  row.p_e_star_kpa = kNaN;
  return row;
}

StateRow MissingRow(const CaseFolder& c) {
  StateRow row = CaseFields(c.record);
  row.kind = TableKind::kNone;
  row.status = TableStatus::kNoResult;
  row.message = c.termination.empty() ? c.message : c.termination + ": " + c.message;
  for (double* v : {&row.psi_epsilon_deg,
                    &row.p_kpa,
                    &row.e,
                    &row.ln_1_plus_e,
                    &row.psi_sigma_deg,
                    &row.q_over_p,
                    &row.ocr,
                    &row.p_e_star_kpa,
                    &row.inertial_number_dmin,
                    &row.inertial_number_dmax,
                    &row.coordination,
                    &row.mechanical_coordination,
                    &row.max_relative_overlap,
                    &row.window_strain,
                    &row.window_lnp,
                    &row.psi_change_deg,
                    &row.slope_change,
                    &row.lnp_change,
                    &row.dln1pe_dlnp,
                    &row.window_p_min_kpa,
                    &row.window_p_max_kpa}) {
    *v = kNaN;
  }
  return row;
}

// A compression path as samples of rising ln p (the running maximum), rows
// that are a gas left out.
PathSamples CompressionPath(const TimeSeries& series, int64_t first, int64_t last) {
  PathSamples path;
  const std::vector<double>& p = series.Values(dem::record::kColumnMeanStress);
  const std::vector<double>& e = series.Values(dem::record::kColumnVoidRatio);
  const std::vector<double>& psi = series.Values(dem::record::kColumnPsiSigma);
  const std::vector<double>& coordination =
      series.Values(dem::record::kColumnMechanicalCoordination);
  for (int64_t r = first; r <= last && r < static_cast<int64_t>(p.size()); ++r) {
    const size_t k = static_cast<size_t>(r);
    if (!(p[k] > 0) || dem::IsGas(p[k], coordination[k])) continue;
    const double x = std::log(p[k]);
    if (!path.x.empty() && x <= path.x.back()) continue;
    path.x.push_back(x);
    path.y.push_back(std::log1p(e[k]));
    path.psi.push_back(psi[k]);
  }
  return path;
}

// An extension path as samples of rising ln(1+e) with ln p, rows below the
// detector's floor left out (their thin network is what an extension state
// is, SPEC §8.4).
PathSamples ExtensionPath(const TimeSeries& series, int64_t first, int64_t last, double floor_kpa) {
  PathSamples path;
  const std::vector<double>& p = series.Values(dem::record::kColumnMeanStress);
  const std::vector<double>& e = series.Values(dem::record::kColumnVoidRatio);
  const std::vector<double>& psi = series.Values(dem::record::kColumnPsiSigma);
  for (int64_t r = first; r <= last && r < static_cast<int64_t>(p.size()); ++r) {
    const size_t k = static_cast<size_t>(r);
    if (!(p[k] >= floor_kpa)) continue;
    const double x = std::log1p(e[k]);
    if (!path.x.empty() && x <= path.x.back()) continue;
    path.x.push_back(x);
    path.y.push_back(std::log(p[k]));
    path.psi.push_back(psi[k]);
  }
  return path;
}

}  // namespace

double Smoothed(const std::vector<double>& x, const std::vector<double>& y, double at, double h) {
  const auto lo = std::lower_bound(x.begin(), x.end(), at - h);
  const auto hi = std::upper_bound(x.begin(), x.end(), at + h);
  if (hi > lo) {
    double sum = 0;
    for (auto it = lo; it != hi; ++it) sum += y[static_cast<size_t>(it - x.begin())];
    return sum / static_cast<double>(hi - lo);
  }
  const auto it = std::lower_bound(x.begin(), x.end(), at);
  if (it == x.begin()) return y.front();
  if (it == x.end()) return y.back();
  const size_t k = static_cast<size_t>(it - x.begin());
  const double t = (at - x[k - 1]) / (x[k] - x[k - 1]);
  return y[k - 1] + t * (y[k] - y[k - 1]);
}

namespace {

// The mean of the two paths' smoothed `y` at `x`.
double MeanAt(const PathSamples& a, const PathSamples& b, std::vector<double> PathSamples::*y,
              double x, double h) {
  return 0.5 * (Smoothed(a.x, a.*y, x, h) + Smoothed(b.x, b.*y, x, h));
}

// Where two paths sampled on one ascending axis join (see JoinPaths): the
// first grid point over the common range [lo, hi] from which y and ψ_σ stay
// within `y_tolerance` and `psi_tolerance` to its end; NaN when they do not
// stay together over a quarter of it.
double JoinedAt(const PathSamples& a, const PathSamples& b, double y_tolerance,
                double psi_tolerance, double h, int n, double lo, double hi) {
  auto grid = [&](int g) { return lo + static_cast<double>(g) / (n - 1) * (hi - lo); };
  int first = n;
  while (first > 0) {
    const double x = grid(first - 1);
    const bool close =
        std::abs(Smoothed(a.x, a.y, x, h) - Smoothed(b.x, b.y, x, h)) < y_tolerance &&
        std::abs(Smoothed(a.x, a.psi, x, h) - Smoothed(b.x, b.psi, x, h)) < psi_tolerance;
    if (!close) break;
    --first;
  }
  return first > n - std::max(2, n / 4) ? kNaN : grid(first);
}

// The common x range of two paths; false (status no_overlap) when none.
bool CommonRange(const PathSamples& a, const PathSamples& b, double* lo, double* hi,
                 ConvergenceRow* row) {
  row->joined_at_p_kpa = row->ln_1_plus_e = row->psi_sigma_deg = kNaN;
  row->overlap_from_p_kpa = row->overlap_to_p_kpa = kNaN;
  row->status = "no_overlap";
  if (a.x.size() < 2 || b.x.size() < 2) return false;
  *lo = std::max(a.x.front(), b.x.front());
  *hi = std::min(a.x.back(), b.x.back());
  return *hi > *lo;
}

}  // namespace

ConvergenceRow JoinPaths(const PathSamples& a, const PathSamples& b,
                         const ConvergenceTolerance& tolerance) {
  ConvergenceRow row;
  double lo = 0, hi = 0;
  if (!CommonRange(a, b, &lo, &hi, &row)) return row;
  row.overlap_from_p_kpa = std::exp(lo);
  row.overlap_to_p_kpa = std::exp(hi);
  const double h = tolerance.smoothing_lnp;
  const double x = JoinedAt(a, b, tolerance.ln_1_plus_e, tolerance.psi_sigma_deg, h,
                            tolerance.grid_points, lo, hi);
  row.status = std::isnan(x) ? "not_joined" : "joined";
  if (std::isnan(x)) return row;
  row.joined_at_p_kpa = std::exp(x);
  row.ln_1_plus_e = MeanAt(a, b, &PathSamples::y, x, h);
  row.psi_sigma_deg = MeanAt(a, b, &PathSamples::psi, x, h);
  return row;
}

ConvergenceRow JoinExtensionPaths(const PathSamples& a, const PathSamples& b,
                                  const ConvergenceTolerance& tolerance) {
  ConvergenceRow row;
  double lo = 0, hi = 0;
  if (!CommonRange(a, b, &lo, &hi, &row)) return row;
  const double h = tolerance.smoothing_ln_1_plus_e;
  row.overlap_from_p_kpa = std::exp(MeanAt(a, b, &PathSamples::y, lo, h));
  row.overlap_to_p_kpa = std::exp(MeanAt(a, b, &PathSamples::y, hi, h));
  const double x =
      JoinedAt(a, b, tolerance.ln_p, tolerance.psi_sigma_deg, h, tolerance.grid_points, lo, hi);
  row.status = std::isnan(x) ? "not_joined" : "joined";
  if (std::isnan(x)) return row;
  row.joined_at_p_kpa = std::exp(MeanAt(a, b, &PathSamples::y, x, h));
  row.ln_1_plus_e = x;
  row.psi_sigma_deg = MeanAt(a, b, &PathSamples::psi, x, h);
  return row;
}

namespace {

// The table's columns in the order of its CSV file: one entry per column
// drives the CSV, the HDF5 file and the reader.
using Member =
    std::variant<int StateRow::*, double StateRow::*, std::string StateRow::*,
                 TableKind StateRow::*, TableStatus StateRow::*, TableSource StateRow::*>;
struct Column {
  const char* name;
  Member member;
  const char* units = "";  // of a number column
  bool optional = false;   // absent from older tables: SetAbsent
};
constexpr bool kOptional = true;
const Column kColumns[] = {
    {table::kColumnReplicate, &StateRow::replicate},
    {table::kColumnKind, &StateRow::kind},
    {table::kColumnStatus, &StateRow::status},
    {table::kColumnCase, &StateRow::case_id},
    {table::kColumnCaseName, &StateRow::case_name},
    {table::kColumnStage, &StateRow::stage},
    {table::kColumnPsiEpsilon, &StateRow::psi_epsilon_deg, "deg"},
    {table::kColumnMeanStress, &StateRow::p_kpa, "kPa"},
    {table::kColumnVoidRatio, &StateRow::e, "1"},
    {table::kColumnLnVolume, &StateRow::ln_1_plus_e, "1"},
    {table::kColumnPsiSigma, &StateRow::psi_sigma_deg, "deg"},
    {table::kColumnStressRatio, &StateRow::q_over_p, "1"},
    {table::kColumnOcr, &StateRow::ocr, "1"},
    {table::kColumnEquivalentPressure, &StateRow::p_e_star_kpa, "kPa"},
    {table::kColumnInertialNumberDmin, &StateRow::inertial_number_dmin, "1"},
    {table::kColumnInertialNumberDmax, &StateRow::inertial_number_dmax, "1"},
    {table::kColumnCoordination, &StateRow::coordination, "1"},
    {table::kColumnMechanicalCoordination, &StateRow::mechanical_coordination, "1"},
    {table::kColumnMaxRelativeOverlap, &StateRow::max_relative_overlap, "1"},
    {table::kColumnWindowStrain, &StateRow::window_strain, "1"},
    {table::kColumnWindowLnp, &StateRow::window_lnp, "1"},
    {table::kColumnPsiChange, &StateRow::psi_change_deg, "deg"},
    {table::kColumnSlopeChange, &StateRow::slope_change, "1"},
    {table::kColumnLnpChange, &StateRow::lnp_change, "1"},
    {table::kColumnSlope, &StateRow::dln1pe_dlnp, "1"},
    {table::kColumnWindowPMin, &StateRow::window_p_min_kpa, "kPa", kOptional},
    {table::kColumnWindowPMax, &StateRow::window_p_max_kpa, "kPa", kOptional},
    {table::kColumnHeldBeforeEnd, &StateRow::held_before_end, "", kOptional},
    {table::kColumnSource, &StateRow::source, "", kOptional},
    {table::kColumnNclReference, &StateRow::ncl_reference},
    {table::kColumnRun, &StateRow::run},
    {table::kColumnFigures, &StateRow::figures},
    {table::kColumnFlags, &StateRow::flags},
    {table::kColumnDetector, &StateRow::detector},
    {table::kColumnMessage, &StateRow::message},
};

// A field of the CSV file.
std::string CsvField(const StateRow& row, const Member& member) {
  return std::visit(
      [&row](auto m) -> std::string {
        using T = std::decay_t<decltype(row.*m)>;
        if constexpr (std::is_same_v<T, int>) {
          return std::to_string(row.*m);
        } else if constexpr (std::is_same_v<T, double>) {
          return CsvNumber(row.*m);
        } else if constexpr (std::is_same_v<T, std::string>) {
          return CsvText(row.*m);
        } else {
          return ToString(row.*m);
        }
      },
      member);
}

void WriteColumn(Hdf5File& file, const std::vector<StateRow>& rows, const Column& column) {
  const std::string path = std::string(table::kStatesGroup) + "/" + column.name;
  std::visit(
      [&](auto m) {
        using T = std::decay_t<decltype(StateRow{}.*m)>;
        if constexpr (std::is_same_v<T, int>) {
          std::vector<int64_t> values;
          for (const StateRow& row : rows) values.push_back(row.*m);
          file.WriteInts(path, values);
        } else if constexpr (std::is_same_v<T, double>) {
          std::vector<double> values;
          for (const StateRow& row : rows) values.push_back(row.*m);
          file.WriteDoubles(path, values, column.units);
        } else {
          std::vector<std::string> values;
          for (const StateRow& row : rows) {
            if constexpr (std::is_same_v<T, std::string>) {
              values.push_back(row.*m);
            } else {
              values.push_back(ToString(row.*m));
            }
          }
          file.WriteStrings(path, values);
        }
      },
      column.member);
}

// Reads one column into `rows` (sized by the replicate column).
void ReadColumn(const Hdf5File& file, const std::string& origin, const Column& column,
                std::vector<StateRow>* rows) {
  const std::string path = std::string(table::kStatesGroup) + "/" + column.name;
  std::visit(
      [&](auto m) {
        using T = std::decay_t<decltype(StateRow{}.*m)>;
        if constexpr (std::is_same_v<T, int>) {
          const std::vector<int64_t> values = file.ReadInts(path);
          for (size_t k = 0; k < rows->size() && k < values.size(); ++k) {
            (*rows)[k].*m = static_cast<int>(values[k]);
          }
        } else if constexpr (std::is_same_v<T, double>) {
          const std::vector<double> values = file.ReadDoubles(path);
          for (size_t k = 0; k < rows->size() && k < values.size(); ++k) (*rows)[k].*m = values[k];
        } else {
          const std::vector<std::string> values = file.ReadStrings(path);
          for (size_t k = 0; k < rows->size() && k < values.size(); ++k) {
            if constexpr (std::is_same_v<T, std::string>) {
              (*rows)[k].*m = values[k];
            } else {
              const std::optional<T> value = FromString<T>(values[k]);
              if (!value) {
                throw InputError(fmt::format("{}: {} of row {} is '{}': expected {}", origin, path,
                                             k + 1, values[k], AllowedNames<T>()));
              }
              (*rows)[k].*m = *value;
            }
          }
        }
      },
      column.member);
}

// A column that a table written before it lacks: NaN for a number, and the
// source a row of those tables has (a path-convergence row or a replicate's).
void SetAbsent(const Column& column, StateRow* row) {
  if (auto m = std::get_if<double StateRow::*>(&column.member)) row->*(*m) = kNaN;
  if (std::holds_alternative<TableSource StateRow::*>(column.member)) {
    row->source =
        row->stage == table::kStageJoined ? TableSource::kJoined : TableSource::kReplicate;
  }
}

void WriteRows(const std::string& directory, const std::vector<StateRow>& rows,
               const std::vector<NclFit>& fits) {
  std::string csv;
  for (const Column& column : kColumns) csv += (csv.empty() ? "" : ",") + std::string(column.name);
  csv += "\n";
  for (const StateRow& row : rows) {
    std::string line;
    for (const Column& column : kColumns) {
      line += (line.empty() ? "" : ",") + CsvField(row, column.member);
    }
    csv += line + "\n";
  }
  WriteTextFileAtomically(directory + "/asymptotic_states.csv", csv);

  Hdf5File file = Hdf5File::CreateAtomic(directory + "/" + table::kFileName);
  file.CreateGroup(table::kStatesGroup);
  file.SetAttribute(table::kStatesGroup, "description",
                    "asymptotic states of every case: one row per detector-carrying stage, and "
                    "one per case without a result; with several replicates, one per stage for "
                    "their ensemble-mean path (source ensemble)");
  for (const Column& column : kColumns) WriteColumn(file, rows, column);
  file.CreateGroup("/ncl_fit");
  std::vector<double> n, lambda, pmin, pmax;
  std::vector<int64_t> reps, points;
  std::vector<std::string> names;
  for (const NclFit& fit : fits) {
    names.push_back(fit.case_name);
    reps.push_back(fit.replicate);
    points.push_back(fit.points);
    n.push_back(fit.valid() ? fit.n : kNaN);
    lambda.push_back(fit.valid() ? fit.lambda : kNaN);
    pmin.push_back(fit.p_min_kpa);
    pmax.push_back(fit.p_max_kpa);
  }
  file.WriteInts("/ncl_fit/replicate", reps);
  file.WriteInts("/ncl_fit/points", points);
  file.WriteStrings("/ncl_fit/case", names);
  file.WriteDoubles("/ncl_fit/N", n, "1");
  file.WriteDoubles("/ncl_fit/lambda_star", lambda, "1");
  file.WriteDoubles("/ncl_fit/p_min_kpa", pmin, "kPa");
  file.WriteDoubles("/ncl_fit/p_max_kpa", pmax, "kPa");
  file.Commit();
}

// The ensemble row's state in a line of the summary (empty fields without one).
std::string EnsembleFields(const StateRow* ensemble) {
  if (!ensemble) return ",,,";
  return "," + std::string(ToString(ensemble->status)) + "," + CsvNumber(ensemble->psi_sigma_deg) +
         "," + CsvNumber(ensemble->ln_1_plus_e);
}

// Mean and 95 % interval over replicates of each (case name, stage), from
// the detected states of the replicates' rows (and the path-convergence
// rows, a group of their own), with the state of the ensemble row beside.
void WriteSummary(const std::string& directory, const std::vector<StateRow>& rows) {
  std::map<std::pair<std::string, std::string>, std::vector<const StateRow*>> groups;
  std::map<std::pair<std::string, std::string>, const StateRow*> ensembles;
  std::vector<std::pair<std::string, std::string>> order;
  for (const StateRow& row : rows) {
    if (row.status == TableStatus::kNoResult) continue;
    const auto key = std::make_pair(row.case_name, row.stage);
    if (row.source == TableSource::kEnsemble) {
      ensembles[key] = &row;
      continue;
    }
    if (!groups.count(key)) order.push_back(key);
    groups[key].push_back(&row);
  }
  const std::pair<const char*, double StateRow::*> summarised[] = {
      {table::kColumnMeanStress, &StateRow::p_kpa},
      {table::kColumnLnVolume, &StateRow::ln_1_plus_e},
      {table::kColumnPsiSigma, &StateRow::psi_sigma_deg},
      {table::kColumnStressRatio, &StateRow::q_over_p},
      {table::kColumnOcr, &StateRow::ocr},
      {table::kColumnPsiEpsilon, &StateRow::psi_epsilon_deg}};
  std::string csv = "case_name,stage,kind,replicates,detected";
  for (const auto& [name, member] : summarised) csv += fmt::format(",{0}_mean,{0}_ci95", name);
  csv += fmt::format(",ensemble_{},ensemble_{},ensemble_{}\n", table::kColumnStatus,
                     table::kColumnPsiSigma, table::kColumnLnVolume);
  for (const auto& key : order) {
    const std::vector<const StateRow*>& members = groups[key];
    std::vector<const StateRow*> detected;
    for (const StateRow* row : members) {
      if (row->status == TableStatus::kDetected) detected.push_back(row);
    }
    csv += CsvText(key.first) + "," + CsvText(key.second) + "," + ToString(members.front()->kind) +
           "," + std::to_string(members.size()) + "," + std::to_string(detected.size());
    for (const auto& [name, member] : summarised) {
      std::vector<double> values;
      for (const StateRow* row : detected) {
        if (std::isfinite(row->*member)) values.push_back(row->*member);
      }
      const Interval interval = MeanInterval95(values);
      csv += "," + CsvNumber(interval.mean) + "," + CsvNumber(interval.half_width);
    }
    const auto ensemble = ensembles.find(key);
    csv += EnsembleFields(ensemble == ensembles.end() ? nullptr : ensemble->second) + "\n";
  }
  WriteTextFileAtomically(directory + "/asymptotic_states_summary.csv", csv);
}

// The state where two paths joined, as a row of the table.
StateRow JoinedRow(const ConvergenceRow& joined, const ConvergenceTolerance& tolerance) {
  StateRow row = MissingRow({});
  row.case_name = joined.case_a + "+" + joined.case_b;
  row.case_id = "r" + std::to_string(joined.replicate) + "/" + row.case_name;
  row.replicate = joined.replicate;
  row.stage = table::kStageJoined;
  row.source = TableSource::kJoined;
  row.kind = joined.kind;
  row.status = TableStatus::kDetected;
  row.message.clear();
  row.detector =
      joined.kind == TableKind::kExtension
          ? fmt::format(
                "path_convergence: extension paths of psi_epsilon = {:g} deg from different "
                "starting states agree within {:g} in ln p and {:g} deg in psi_sigma at a common "
                "ln(1+e) (averaged over +-{:g} in ln(1+e), p >= the detector's floor) from here "
                "on, over at least a quarter of their common range",
                joined.psi_epsilon_deg, tolerance.ln_p, tolerance.psi_sigma_deg,
                tolerance.smoothing_ln_1_plus_e)
          : fmt::format(
                "path_convergence: paths of psi_epsilon = {:g} deg from different starting states "
                "agree within {:g} in ln(1+e) and {:g} deg in psi_sigma (averaged over +-{:g} in "
                "ln p) from here on, over at least a quarter of their common range",
                joined.psi_epsilon_deg, tolerance.ln_1_plus_e, tolerance.psi_sigma_deg,
                tolerance.smoothing_lnp);
  row.psi_epsilon_deg = joined.psi_epsilon_deg;
  row.p_kpa = joined.joined_at_p_kpa;
  row.ln_1_plus_e = joined.ln_1_plus_e;
  row.e = std::expm1(joined.ln_1_plus_e);
  row.psi_sigma_deg = joined.psi_sigma_deg;
  row.q_over_p = 3.0 / std::sqrt(2.0) * std::tan(joined.psi_sigma_deg * M_PI / 180.0);
  // The paths agree from where they joined to the end of their common range.
  row.window_p_min_kpa = std::min(joined.joined_at_p_kpa, joined.overlap_to_p_kpa);
  row.window_p_max_kpa = std::max(joined.joined_at_p_kpa, joined.overlap_to_p_kpa);
  return row;
}

}  // namespace

std::string CsvText(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c == '\n' ? ' ' : c;
  }
  return out + "\"";
}

std::string CsvNumber(double value) {
  if (std::isnan(value)) return "";
  return fmt::format("{:.10g}", value);
}

Interval MeanInterval95(const std::vector<double>& values) {
  Interval interval{kNaN, kNaN};
  if (values.empty()) return interval;
  interval.mean = 0;
  for (double v : values) interval.mean += v;
  interval.mean /= static_cast<double>(values.size());
  if (values.size() < 2) return interval;
  double var = 0;
  for (double v : values) var += (v - interval.mean) * (v - interval.mean);
  var /= static_cast<double>(values.size() - 1);
  interval.half_width = StudentT95(static_cast<int>(values.size()) - 1) *
                        std::sqrt(var / static_cast<double>(values.size()));
  return interval;
}

namespace {

// A compression or extension path of one case, for the convergence check,
// with the rate and validity of its stage's row (which a joined state takes).
struct ConvergencePath {
  std::string case_name;
  double start_p = 0;
  PathSamples samples;
  double inertial_number_dmin = kNaN, inertial_number_dmax = kNaN;
  std::string flags;
};
// Paths by (replicate, kind, ψ_ε, material and rate): only paths of one
// material at one rate can join (a rate sweep's paths from one start at two
// rates agree during their first, elastic unloading: no normal line).
using PathGroups =
    std::map<std::tuple<int, TableKind, double, std::string>, std::vector<ConvergencePath>>;

// What a path's group needs besides its direction: the contact material and
// the stage's rate ("E 5e+08 ... | inertial 0.001").
// A result without provenance (older than the run layer) names no material:
// its paths group by rate alone.
std::string MaterialAndRate(const Hdf5File& file, size_t stage) {
  const std::string rate = dem::StageRateLabel(file, stage);
  if (!file.HasAttribute(dem::record::kProvenance, dem::record::kSceneSha256)) {
    return "material not recorded | " + rate;
  }
  const dem::Material m = dem::ReadMaterial(file);
  return fmt::format("E {:g} s {:g} kt/kn {:g} nu {:g} phi {:g} mu_r {:g} rho {:g} chi {:g} | {}",
                     m.youngs_modulus, m.stiffness_scaling, m.stiffness_ratio, m.poissons_ratio,
                     m.friction_angle, m.rolling_friction, m.density, m.local_damping, rate);
}

// The replicates of one (case name, stage) for its ensemble-mean path: the
// row's case fields and each replicate's stage.
struct EnsembleGroup {
  StateRow fields;
  std::vector<ReplicateStage> replicates;
};

// What the case folders give the tables: the rows of every case (a row per
// detector-carrying stage, one per case without a result), its compression
// and extension paths, each case's parent (also under replicate 0, for the
// ensemble rows) and the replicates of each stage.
struct CaseTables {
  std::vector<StateRow> rows;
  PathGroups paths;
  std::map<std::pair<int, std::string>, std::string> parent_of;  // (replicate, case) → parent
  std::vector<EnsembleGroup> ensembles;                          // in the order first seen
  std::map<std::pair<std::string, std::string>, size_t> ensemble_of;  // (case, stage) → index
};

// A compression or extension stage's path for the convergence check.
void AddConvergencePath(const CaseFolder& c, const dem::StageRecord& stage, const StateRow& row,
                        const TimeSeries& series, const std::string& material_and_rate,
                        PathGroups* paths) {
  if (row.kind != TableKind::kCompression && row.kind != TableKind::kExtension) return;
  const bool rising = row.kind == TableKind::kCompression;
  ConvergencePath path;
  path.case_name = c.record.name;
  path.samples = rising ? CompressionPath(series, stage.first_row, stage.last_row)
                        : ExtensionPath(series, stage.first_row, stage.last_row,
                                        stage.asymptote->criterion.floor_kpa);
  if (path.samples.x.size() < 2) return;
  path.start_p = std::exp(rising ? path.samples.x.front() : path.samples.y.front());
  path.inertial_number_dmin = row.inertial_number_dmin;
  path.inertial_number_dmax = row.inertial_number_dmax;
  path.flags = row.flags;
  const double psi = std::round(row.psi_epsilon_deg * 1e6) / 1e6;
  (*paths)[{c.record.replicate, row.kind, psi, material_and_rate}].push_back(std::move(path));
}

// Stage `index` of a replicate's result, with the path its detector sampled,
// into the group of its case name and stage.
void AddToEnsemble(const CaseFolder& c, const Hdf5File& file,
                   const std::vector<dem::StageRecord>& stages, size_t index,
                   const TimeSeries& series, CaseTables* tables) {
  const dem::StageRecord& stage = stages[index];
  const auto key = std::make_pair(c.record.name, stage.name);
  if (!tables->ensemble_of.count(key)) {
    EnsembleGroup group;
    group.fields = CaseFields(c.record);
    group.fields.replicate = 0;
    group.fields.case_id = table::kEnsembleCasePrefix + c.record.name;
    group.fields.source = TableSource::kEnsemble;
    tables->ensemble_of[key] = tables->ensembles.size();
    tables->ensembles.push_back(std::move(group));
  }
  ReplicateStage replicate{
      stage, ReadStagePath(series, DetectionFirstRow(file, stages, index), stage.last_row),
      StopsAtAsymptote(file, stages, index)};
  replicate.record.end_state.reset();
  tables->ensembles[tables->ensemble_of[key]].replicates.push_back(std::move(replicate));
}

// The rows, paths and replicate stages of a finished case.
void ReadResult(const CaseFolder& c, CaseTables* tables) {
  const Hdf5File file = Hdf5File::OpenRead(c.record.result_path());
  const std::vector<dem::StageRecord> stages = dem::ReadStageRecords(file);
  std::optional<TimeSeries> series;
  bool any = false;
  for (size_t k = 0; k < stages.size(); ++k) {
    const dem::StageRecord& stage = stages[k];
    if (!stage.asymptote) continue;
    any = true;
    StateRow row = RowFrom(CaseFields(c.record), stage);
    if (c.termination != "completed" && row.message.empty()) row.message = c.message;
    tables->rows.push_back(row);
    if (!series) series = TimeSeries::Read(file, dem::record::kSeries);
    AddConvergencePath(c, stage, row, *series, MaterialAndRate(file, k), &tables->paths);
    AddToEnsemble(c, file, stages, k, *series, tables);
  }
  if (!any && c.termination != "completed") tables->rows.push_back(MissingRow(c));
}

void ReadCases(const std::string& directory, CaseTables* tables) {
  for (const CaseFolder& c : ListCases(directory)) {
    tables->parent_of[{c.record.replicate, c.record.name}] = c.record.parent_name();
    tables->parent_of[{0, c.record.name}] = c.record.parent_name();
    if (c.finished) {
      ReadResult(c, tables);
    } else {
      tables->rows.push_back(MissingRow(c));
    }
  }
}

// The rows of the replicates' ensemble-mean paths (issue 34 §3): one per
// (case name, stage) with two replicates or more.
std::vector<StateRow> EnsembleRows(const std::vector<EnsembleGroup>& groups) {
  std::vector<StateRow> rows;
  for (const EnsembleGroup& group : groups) {
    if (group.replicates.size() < 2) continue;
    rows.push_back(RowFrom(group.fields, EnsembleStageRecord(group.replicates)));
  }
  return rows;
}

// A joined state's inertial numbers and flags from the rows of the paths it
// joins: the larger I of the two (NaN when either is unknown: a state is no
// slower than its faster path) and the union of their flags, in order.
void TakeRateOfJoinedPaths(const ConvergencePath& a, const ConvergencePath& b, StateRow* joined) {
  const auto larger = [](double x, double y) {
    return std::isfinite(x) && std::isfinite(y) ? std::max(x, y) : kNaN;
  };
  joined->inertial_number_dmin = larger(a.inertial_number_dmin, b.inertial_number_dmin);
  joined->inertial_number_dmax = larger(a.inertial_number_dmax, b.inertial_number_dmax);
  std::vector<std::string> flags;
  for (const std::string* list : {&a.flags, &b.flags}) {
    std::stringstream in(*list);
    std::string flag;
    while (std::getline(in, flag, table::kFlagSeparator)) {
      if (!flag.empty() && std::find(flags.begin(), flags.end(), flag) == flags.end())
        flags.push_back(flag);
    }
  }
  joined->flags.clear();
  for (const std::string& flag : flags) {
    joined->flags += (joined->flags.empty() ? "" : std::string(1, table::kFlagSeparator)) + flag;
  }
}

// Paper Sec. 4.3: paths of one ψ_ε from successive starting states; a joined
// pair adds its state to `rows`, with the larger I and the flags of both
// paths' rows.
std::vector<ConvergenceRow> JoinGroups(PathGroups* paths, const ConvergenceTolerance& tolerance,
                                       std::vector<StateRow>* rows, StateTableSummary* summary) {
  std::vector<ConvergenceRow> convergence;
  for (auto& [key, group] : *paths) {
    const auto& [replicate, kind, psi, material_and_rate] = key;
    const bool rising = kind == TableKind::kCompression;
    std::sort(group.begin(), group.end(), [](const ConvergencePath& a, const ConvergencePath& b) {
      return a.start_p < b.start_p;
    });
    for (size_t k = 1; k < group.size(); ++k) {
      ConvergenceRow row =
          rising ? JoinPaths(group[k - 1].samples, group[k].samples, tolerance)
                 : JoinExtensionPaths(group[k - 1].samples, group[k].samples, tolerance);
      row.replicate = replicate;
      row.kind = kind;
      row.psi_epsilon_deg = psi;
      row.case_a = group[k - 1].case_name;
      row.case_b = group[k].case_name;
      summary->joined += row.status == "joined";
      summary->not_joined += row.status != "joined";
      convergence.push_back(row);
      if (row.status == "joined") {
        rows->push_back(JoinedRow(row, tolerance));
        TakeRateOfJoinedPaths(group[k - 1], group[k], &rows->back());
      }
    }
  }
  return convergence;
}

// An NCL per replicate and NCL-carrying case (the study's NCL, and the
// NCLs of samples with another material or time step: cases with NCL
// states at two stages or more; a case that continues an NC state to one
// isotropic asymptote, as the rate study's ψ_ε = 0° cases do, refers to
// its ancestor's NCL), through the stage-end states that are load-bearing
// and reliable: detected or drifting (the detector's ψ_σ and slope tests
// are at the noise of a small sample on a ψ_ε = 0° path), not a gas,
// overlaps below 10 %. Returns (replicate, case) → index into `fits`.
std::map<std::pair<int, std::string>, size_t> FitNcls(const std::vector<StateRow>& rows,
                                                      const std::string& ncl_case,
                                                      std::vector<NclFit>* fits) {
  std::map<std::pair<int, std::string>, int> ncl_states;  // (replicate, case) → NCL rows
  for (const StateRow& row : rows) {
    if (row.kind == TableKind::kNcl) ++ncl_states[{row.replicate, row.case_name}];
  }
  std::map<std::pair<int, std::string>, size_t> fit_of;
  for (const StateRow& row : rows) {
    const auto key = std::make_pair(row.replicate, row.case_name);
    if (row.kind != TableKind::kNcl || fit_of.count(key)) continue;
    if (ncl_states[key] < 2 && row.case_name != ncl_case) continue;
    NclFit fit;
    fit.replicate = row.replicate;
    fit.case_name = row.case_name;
    std::vector<double> x, y;
    for (const StateRow& other : rows) {
      if (other.replicate != fit.replicate || other.case_name != fit.case_name ||
          other.kind != TableKind::kNcl ||
          (other.status != TableStatus::kDetected && other.status != TableStatus::kDrifting) ||
          other.flags.find("overlap_above_10pct") != std::string::npos) {
        continue;
      }
      ++(other.status == TableStatus::kDetected ? fit.detected : fit.drifting);
      x.push_back(std::log(other.p_kpa));
      y.push_back(other.ln_1_plus_e);
    }
    fit.points = static_cast<int>(x.size());
    const LineFit line = FitLine(x, y);
    if (line.valid()) {
      fit.n = line.intercept;
      fit.lambda = -line.slope;
      fit.p_min_kpa = std::exp(*std::min_element(x.begin(), x.end()));
      fit.p_max_kpa = std::exp(*std::max_element(x.begin(), x.end()));
    }
    fit_of[key] = fits->size();
    fits->push_back(fit);
  }
  return fit_of;
}

// Each state refers to the NCL of its nearest ancestor (or itself) that has
// one, else to the study's NCL: its p_e* and OCR.
void ReferToNcls(const std::vector<NclFit>& fits,
                 const std::map<std::pair<int, std::string>, size_t>& fit_of,
                 const std::map<std::pair<int, std::string>, std::string>& parent_of,
                 const std::string& ncl_case, std::vector<StateRow>* rows) {
  for (StateRow& row : *rows) {
    if (!(row.p_kpa > 0)) continue;
    std::string name = row.case_name.substr(0, row.case_name.find('+'));  // joined: first path
    const NclFit* fit = nullptr;
    for (int guard = 0; !name.empty() && guard < 1000; ++guard) {
      const auto it = fit_of.find({row.replicate, name});
      if (it != fit_of.end() && fits[it->second].valid()) {
        fit = &fits[it->second];
        break;
      }
      const auto up = parent_of.find({row.replicate, name});
      name = up == parent_of.end() ? "" : up->second;
    }
    if (!fit) {
      const auto it = fit_of.find({row.replicate, ncl_case});
      if (it != fit_of.end() && fits[it->second].valid()) fit = &fits[it->second];
    }
    if (!fit) continue;
    row.ncl_reference = fit->case_name;
    row.p_e_star_kpa = std::exp((fit->n - row.ln_1_plus_e) / fit->lambda);
    row.ocr = row.p_e_star_kpa / row.p_kpa;
  }
}

void WriteNclFits(const std::string& directory, const std::vector<NclFit>& fits) {
  std::string csv = "replicate,case,points,detected,drifting,N,lambda_star,p_min_kpa,p_max_kpa\n";
  for (const NclFit& fit : fits) {
    csv += fmt::format("{},{},{},{},{},{},{},{},{}\n", fit.replicate, fit.case_name, fit.points,
                       fit.detected, fit.drifting, CsvNumber(fit.valid() ? fit.n : kNaN),
                       CsvNumber(fit.valid() ? fit.lambda : kNaN), CsvNumber(fit.p_min_kpa),
                       CsvNumber(fit.p_max_kpa));
  }
  WriteTextFileAtomically(directory + "/ncl_fit.csv", csv);
}

void WriteConvergence(const std::string& directory, const std::vector<ConvergenceRow>& rows,
                      const ConvergenceTolerance& tolerance) {
  std::string csv = fmt::format(
      "# paths of one psi_epsilon from different starting states join where ln(1+e) and "
      "psi_sigma agree within {} and {} deg at a common p from there on\n"
      "replicate,kind,psi_epsilon_deg,case_a,case_b,status,joined_at_p_kpa,ln_1_plus_e,"
      "psi_sigma_deg,overlap_from_p_kpa,overlap_to_p_kpa\n",
      tolerance.ln_1_plus_e, tolerance.psi_sigma_deg);
  for (const ConvergenceRow& row : rows) {
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", row.replicate, ToString(row.kind),
                       CsvNumber(row.psi_epsilon_deg), row.case_a, row.case_b, row.status,
                       CsvNumber(row.joined_at_p_kpa), CsvNumber(row.ln_1_plus_e),
                       CsvNumber(row.psi_sigma_deg), CsvNumber(row.overlap_from_p_kpa),
                       CsvNumber(row.overlap_to_p_kpa));
  }
  WriteTextFileAtomically(directory + "/path_convergence.csv", csv);
}

}  // namespace

StateTableSummary WriteStateTable(const std::string& directory,
                                  const ConvergenceTolerance& tolerance) {
  if (!fs::exists(directory + "/study.toml")) {
    throw InputError(directory + ": not a study folder (no study.toml)");
  }
  const std::string ncl_case = StudyNclCase(directory).value_or("");
  StateTableSummary summary;
  summary.directory = directory;
  CaseTables tables;
  ReadCases(directory, &tables);
  std::vector<StateRow>& rows = tables.rows;
  const std::vector<StateRow> ensemble = EnsembleRows(tables.ensembles);
  tables.ensembles.clear();
  rows.insert(rows.end(), ensemble.begin(), ensemble.end());
  const std::vector<ConvergenceRow> convergence =
      JoinGroups(&tables.paths, tolerance, &rows, &summary);
  const auto fit_of = FitNcls(rows, ncl_case, &summary.ncl);
  ReferToNcls(summary.ncl, fit_of, tables.parent_of, ncl_case, &rows);
  WriteNclFits(directory, summary.ncl);
  WriteConvergence(directory, convergence, tolerance);
  for (const StateRow& row : rows) {
    auto& counts = row.source == TableSource::kEnsemble ? summary.ensemble_counts : summary.counts;
    ++counts[ToString(row.kind)][ToString(row.status)];
  }
  WriteRows(directory, rows, summary.ncl);
  WriteSummary(directory, rows);
  return summary;
}

std::vector<StateRow> ReadStateTable(const std::string& directory) {
  const std::string origin = directory + "/" + table::kFileName;
  const Hdf5File file = Hdf5File::OpenRead(origin);
  const std::vector<int64_t> replicates =
      file.ReadInts(std::string(table::kStatesGroup) + "/" + table::kColumnReplicate);
  std::vector<StateRow> rows(replicates.size());
  for (const Column& column : kColumns) {
    if (column.optional && !file.Exists(std::string(table::kStatesGroup) + "/" + column.name)) {
      for (StateRow& row : rows) SetAbsent(column, &row);
      continue;
    }
    ReadColumn(file, origin, column, &rows);
  }
  return rows;
}

std::vector<StateTableColumn> StateTableColumns(const std::vector<StateRow>& rows) {
  std::vector<StateTableColumn> columns;
  for (const Column& column : kColumns) {
    StateTableColumn out;
    out.name = column.name;
    std::visit(
        [&](auto m) {
          using T = std::decay_t<decltype(StateRow{}.*m)>;
          if constexpr (std::is_same_v<T, int> || std::is_same_v<T, double>) {
            if constexpr (std::is_same_v<T, double>) out.units = column.units;
            out.integer = std::is_same_v<T, int>;
            for (const StateRow& row : rows) out.numbers.push_back(row.*m);
          } else {
            out.text = true;
            for (const StateRow& row : rows) {
              if constexpr (std::is_same_v<T, std::string>) {
                out.texts.push_back(row.*m);
              } else {
                out.texts.push_back(ToString(row.*m));
              }
            }
          }
        },
        column.member);
    columns.push_back(std::move(out));
  }
  return columns;
}

std::vector<StateRow> WithoutEnsembleRows(std::vector<StateRow> rows) {
  rows.erase(
      std::remove_if(rows.begin(), rows.end(),
                     [](const StateRow& row) { return row.source == TableSource::kEnsemble; }),
      rows.end());
  return rows;
}

namespace {

// One line per kind: the rows by status.
std::string CountLines(const std::map<std::string, std::map<std::string, int>>& counts,
                       const std::string& indent) {
  std::string text;
  for (const auto& [kind, statuses] : counts) {
    text += fmt::format("{}{:<12}", indent, kind);
    for (const auto& [status, count] : statuses) text += fmt::format(" {} {}", count, status);
    text += "\n";
  }
  return text;
}

}  // namespace

std::string StateTableSummary::Text() const {
  std::string text = "asymptotic states (" + directory + "/asymptotic_states.csv):\n";
  text += CountLines(counts, "  ");
  if (!ensemble_counts.empty()) {
    text += "  ensemble means (the replicates' mean paths through the detector):\n";
    text += CountLines(ensemble_counts, "    ");
  }
  for (const NclFit& fit : ncl) {
    const std::string name =
        (fit.replicate == 0 ? std::string("mean") : "r" + std::to_string(fit.replicate)) + " " +
        fit.case_name;
    text += fit.valid()
                ? fmt::format(
                      "  NCL {}: N = {:.4f}, lambda* = {:.4f} through {} states "
                      "({} detected, {} drifting), {:.4g}-{:.4g} kPa\n",
                      name, fit.n, fit.lambda, fit.points, fit.detected, fit.drifting,
                      fit.p_min_kpa, fit.p_max_kpa)
                : fmt::format("  NCL {}: not determined ({} usable states)\n", name, fit.points);
  }
  text += fmt::format("  path convergence: {} pairs joined, {} not\n", joined, not_joined);
  return text;
}

}  // namespace granasym::study
