#include "study/state_table.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <set>

#include <fmt/format.h>

#include "common/config.h"
#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/text_file.h"
#include "common/time_series.h"
#include "common/statistics.h"
#include "dem/run_record.h"
#include "dem/run_record_names.h"
#include "dem/stage_validity.h"
#include "study/rate_study.h"
#include "study/state_table_names.h"
#include "study/study_folder.h"

namespace granasym::study {
namespace fs = std::filesystem;
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The kind of an asymptotic state, as the table names it.
std::string KindOf(dem::PathKind path, double psi_epsilon_deg) {
  switch (path) {
    case dem::PathKind::kIsochoric:
      return "csl";
    case dem::PathKind::kCompression:
      return std::abs(psi_epsilon_deg) < 1e-6 ? "ncl" : "compression";
    case dem::PathKind::kExtension:
      return "extension";
    case dem::PathKind::kStressControlled:
      return "triaxial";
  }
  return "unknown";
}

struct CaseFolder {
  std::string directory, id, name, run, figures, key;
  std::string parent_name;  // empty: the sample
  int replicate = 1;
  bool finished = false;  // done.toml for the current key, and a result
  std::string termination, message;
};

std::vector<CaseFolder> ListCases(const std::string& directory) {
  std::vector<CaseFolder> cases;
  for (const std::string& path : CaseFolders(directory)) {
    const fs::path folder(path);
    const ConfigTable record = ConfigTable::ParseFile((folder / "case.toml").string());
    CaseFolder c;
    c.directory = folder.string();
    c.id = record.GetString("id");
    c.name = record.GetString("name");
    c.run = record.GetString("run", "");
    c.figures = record.GetString("figures", "");
    c.key = record.GetString("key");
    const std::string parent = record.GetString("parent", "");  // "r<K>/<name>"
    c.parent_name = parent.substr(parent.find('/') + 1);
    c.replicate = static_cast<int>(record.GetInt("replicate", 1, Range::AtLeast(1)));
    if (fs::exists(folder / "done.toml")) {
      const ConfigTable done = ConfigTable::ParseFile((folder / "done.toml").string());
      c.termination = done.GetString("termination");
      c.message = done.GetString("message", "");
      c.finished = done.GetString("key") == c.key && fs::exists(folder / "result.h5");
      if (c.finished) {
        // A partial result under the final name is not the case's result.
        const std::string mismatch =
            ResultMismatch((folder / "result.h5").string(), *ReadDone(c.directory));
        if (!mismatch.empty()) {
          c.finished = false;
          c.message = mismatch;
        }
      }
    }
    if (!c.finished && c.message.empty()) {
      c.message = fs::exists(folder / "result.h5.ckpt") ? "interrupted: resumes on the next run"
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
    if (!(value < tolerance)) failed.push_back(fmt::format("{} {:.3g} (< {:g})", what, value, tolerance));
  };
  check(a.psi_change_deg, c.psi_tolerance_deg, "psi_sigma changed by deg");
  switch (a.path_kind) {
    case dem::PathKind::kIsochoric:
      check(a.lnp_change, c.lnp_tolerance, "ln p changed by");
      break;
    case dem::PathKind::kCompression:
    case dem::PathKind::kExtension:
      check(a.slope_change, c.slope_tolerance, "d ln(1+e)/d ln p changed by a fraction");
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

StateRow RowFrom(const CaseFolder& c, const dem::StageRecord& stage) {
  const dem::AsymptoteRecord& a = *stage.asymptote;
  StateRow row;
  row.case_id = c.id;
  row.case_name = c.name;
  row.run = c.run;
  row.figures = c.figures;
  row.replicate = c.replicate;
  row.stage = stage.name;
  row.kind = KindOf(a.path_kind, a.psi_epsilon_deg);
  row.status = ToString(a.status);
  row.detector = stage.asymptote_criterion;
  for (dem::ValidityFlag flag : stage.validity.flags) {
    row.flags += std::string(row.flags.empty() ? "" : ";") + ToString(flag);
  }
  row.message = stage.stop_reason;
  if (a.status == dem::AsymptoteStatus::kDrifting) row.message = DriftReason(a) + "; " + row.message;
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
  row.ocr = kNaN;
  row.p_e_star_kpa = kNaN;
  return row;
}

StateRow MissingRow(const CaseFolder& c) {
  StateRow row;
  row.case_id = c.id;
  row.case_name = c.name;
  row.run = c.run;
  row.figures = c.figures;
  row.replicate = c.replicate;
  row.kind = "none";
  row.status = "no_result";
  row.message = c.termination.empty() ? c.message : c.termination + ": " + c.message;
  for (double* v : {&row.psi_epsilon_deg, &row.p_kpa, &row.e, &row.ln_1_plus_e, &row.psi_sigma_deg,
                    &row.q_over_p, &row.ocr, &row.p_e_star_kpa, &row.inertial_number_dmin,
                    &row.inertial_number_dmax, &row.coordination, &row.mechanical_coordination,
                    &row.max_relative_overlap, &row.window_strain, &row.window_lnp,
                    &row.psi_change_deg, &row.slope_change, &row.lnp_change, &row.dln1pe_dlnp}) {
    *v = kNaN;
  }
  return row;
}

// A path as monotone samples in x = ln p (the running extreme in the
// direction the path moves: rising for compression, falling for extension).
PathSamples MonotonePath(const TimeSeries& series, int64_t first, int64_t last, bool rising) {
  PathSamples path;
  const std::vector<double>& p = series.Values(dem::record::kColumnMeanStress);
  const std::vector<double>& e = series.Values(dem::record::kColumnVoidRatio);
  const std::vector<double>& psi = series.Values(dem::record::kColumnPsiSigma);
  const std::vector<double>& coordination = series.Values("mechanical_coordination");
  for (int64_t r = first; r <= last && r < static_cast<int64_t>(p.size()); ++r) {
    const size_t k = static_cast<size_t>(r);
    if (!(p[k] > 0) || dem::IsGas(p[k], coordination[k])) continue;
    const double x = std::log(p[k]);
    if (!path.x.empty() && (rising ? x <= path.x.back() : x >= path.x.back())) continue;
    path.x.push_back(x);
    path.ln_v.push_back(std::log1p(e[k]));
    path.psi.push_back(psi[k]);
  }
  if (!rising) {  // ascending x for interpolation
    std::reverse(path.x.begin(), path.x.end());
    std::reverse(path.ln_v.begin(), path.ln_v.end());
    std::reverse(path.psi.begin(), path.psi.end());
  }
  return path;
}

// y at `at`: the mean of the samples within ±h in x (the fluctuations of a
// small sample smoothed), or linear interpolation where none is that close.
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

}  // namespace

ConvergenceRow JoinPaths(const PathSamples& a, const PathSamples& b, bool rising,
                         const ConvergenceTolerance& tolerance) {
  ConvergenceRow row;
  row.joined_at_p_kpa = row.ln_1_plus_e = row.psi_sigma_deg = kNaN;
  row.overlap_from_p_kpa = row.overlap_to_p_kpa = kNaN;
  if (a.x.size() < 2 || b.x.size() < 2) {
    row.status = "no_overlap";
    return row;
  }
  const double lo = std::max(a.x.front(), b.x.front()), hi = std::min(a.x.back(), b.x.back());
  if (!(hi > lo)) {
    row.status = "no_overlap";
    return row;
  }
  row.overlap_from_p_kpa = std::exp(rising ? lo : hi);
  row.overlap_to_p_kpa = std::exp(rising ? hi : lo);
  const int n = tolerance.grid_points;
  const double h = tolerance.smoothing_lnp;
  std::vector<bool> close(static_cast<size_t>(n));
  for (int g = 0; g < n; ++g) {
    // Grid in the direction of travel.
    const double t = static_cast<double>(g) / (n - 1);
    const double x = rising ? lo + t * (hi - lo) : hi - t * (hi - lo);
    close[static_cast<size_t>(g)] =
        std::abs(Smoothed(a.x, a.ln_v, x, h) - Smoothed(b.x, b.ln_v, x, h)) <
            tolerance.ln_1_plus_e &&
        std::abs(Smoothed(a.x, a.psi, x, h) - Smoothed(b.x, b.psi, x, h)) <
            tolerance.psi_sigma_deg;
  }
  int first = n;
  while (first > 0 && close[static_cast<size_t>(first - 1)]) --first;
  // Joined only if the paths stay together over at least a quarter of the range.
  if (first > n - std::max(2, n / 4)) {
    row.status = "not_joined";
    return row;
  }
  const double t = static_cast<double>(first) / (n - 1);
  const double x = rising ? lo + t * (hi - lo) : hi - t * (hi - lo);
  row.status = "joined";
  row.joined_at_p_kpa = std::exp(x);
  row.ln_1_plus_e = 0.5 * (Smoothed(a.x, a.ln_v, x, h) + Smoothed(b.x, b.ln_v, x, h));
  row.psi_sigma_deg = 0.5 * (Smoothed(a.x, a.psi, x, h) + Smoothed(b.x, b.psi, x, h));
  return row;
}

namespace {

struct NumberColumn {
  const char* name;
  const char* units;
  double StateRow::*member;
};
constexpr NumberColumn kNumberColumns[] = {
    {table::kColumnPsiEpsilon, "deg", &StateRow::psi_epsilon_deg},
    {table::kColumnMeanStress, "kPa", &StateRow::p_kpa},
    {table::kColumnVoidRatio, "1", &StateRow::e},
    {table::kColumnLnVolume, "1", &StateRow::ln_1_plus_e},
    {table::kColumnPsiSigma, "deg", &StateRow::psi_sigma_deg},
    {table::kColumnStressRatio, "1", &StateRow::q_over_p},
    {table::kColumnOcr, "1", &StateRow::ocr},
    {table::kColumnEquivalentPressure, "kPa", &StateRow::p_e_star_kpa},
    {table::kColumnInertialNumberDmin, "1", &StateRow::inertial_number_dmin},
    {table::kColumnInertialNumberDmax, "1", &StateRow::inertial_number_dmax},
    {table::kColumnCoordination, "1", &StateRow::coordination},
    {table::kColumnMechanicalCoordination, "1", &StateRow::mechanical_coordination},
    {table::kColumnMaxRelativeOverlap, "1", &StateRow::max_relative_overlap},
    {table::kColumnWindowStrain, "1", &StateRow::window_strain},
    {table::kColumnWindowLnp, "1", &StateRow::window_lnp},
    {table::kColumnPsiChange, "deg", &StateRow::psi_change_deg},
    {table::kColumnSlopeChange, "1", &StateRow::slope_change},
    {table::kColumnLnpChange, "1", &StateRow::lnp_change},
    {table::kColumnSlope, "1", &StateRow::dln1pe_dlnp},
};
struct TextColumn {
  const char* name;
  std::string StateRow::*member;
};
constexpr TextColumn kTextColumns[] = {
    {table::kColumnKind, &StateRow::kind},       {table::kColumnStatus, &StateRow::status},
    {table::kColumnCase, &StateRow::case_id},    {table::kColumnCaseName, &StateRow::case_name},
    {table::kColumnStage, &StateRow::stage},     {table::kColumnRun, &StateRow::run},
    {table::kColumnFigures, &StateRow::figures}, {table::kColumnFlags, &StateRow::flags},
    {table::kColumnDetector, &StateRow::detector}, {table::kColumnMessage, &StateRow::message},
    {table::kColumnNclReference, &StateRow::ncl_reference},
};

void WriteRows(const std::string& directory, const std::vector<StateRow>& rows,
               const std::vector<NclFit>& fits) {
  std::string csv = "replicate,kind,status,case,case_name,stage";
  for (const NumberColumn& column : kNumberColumns) csv += std::string(",") + column.name;
  csv += ",ncl_reference,run,figures,flags,detector,message\n";
  for (const StateRow& row : rows) {
    csv += std::to_string(row.replicate) + "," + row.kind + "," + row.status + "," +
           CsvText(row.case_id) + "," + CsvText(row.case_name) + "," + CsvText(row.stage);
    for (const NumberColumn& column : kNumberColumns) csv += "," + CsvNumber(row.*column.member);
    csv += "," + CsvText(row.ncl_reference) + "," + CsvText(row.run) + "," + CsvText(row.figures) + "," + CsvText(row.flags) + "," +
           CsvText(row.detector) + "," + CsvText(row.message) + "\n";
  }
  WriteTextFileAtomically(directory + "/asymptotic_states.csv", csv);

  Hdf5File file = Hdf5File::CreateAtomic(directory + "/" + table::kFileName);
  file.CreateGroup(table::kStatesGroup);
  file.SetAttribute(table::kStatesGroup, "description",
                    "asymptotic states of every case: one row per detector-carrying stage, and "
                    "one per case without a result");
  std::vector<int64_t> replicates;
  for (const StateRow& row : rows) replicates.push_back(row.replicate);
  file.WriteInts(std::string(table::kStatesGroup) + "/" + table::kColumnReplicate, replicates);
  for (const NumberColumn& column : kNumberColumns) {
    std::vector<double> values;
    for (const StateRow& row : rows) values.push_back(row.*column.member);
    file.WriteDoubles(std::string(table::kStatesGroup) + "/" + column.name, values, column.units);
  }
  for (const TextColumn& column : kTextColumns) {
    std::vector<std::string> values;
    for (const StateRow& row : rows) values.push_back(row.*column.member);
    file.WriteStrings(std::string(table::kStatesGroup) + "/" + column.name, values);
  }
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

// Mean and 95 % interval over replicates of each (case name, stage), from
// the detected states.
void WriteSummary(const std::string& directory, const std::vector<StateRow>& rows) {
  std::map<std::pair<std::string, std::string>, std::vector<const StateRow*>> groups;
  std::vector<std::pair<std::string, std::string>> order;
  for (const StateRow& row : rows) {
    if (row.status == "no_result") continue;
    const auto key = std::make_pair(row.case_name, row.stage);
    if (!groups.count(key)) order.push_back(key);
    groups[key].push_back(&row);
  }
  const std::vector<NumberColumn> summarised = {
      kNumberColumns[1], kNumberColumns[3], kNumberColumns[4],
      kNumberColumns[5], kNumberColumns[6], kNumberColumns[0]};
  std::string csv = "case_name,stage,kind,replicates,detected";
  for (const NumberColumn& column : summarised) {
    csv += fmt::format(",{0}_mean,{0}_ci95", column.name);
  }
  csv += "\n";
  for (const auto& key : order) {
    const std::vector<const StateRow*>& members = groups[key];
    std::vector<const StateRow*> detected;
    for (const StateRow* row : members) {
      if (row->status == "detected") detected.push_back(row);
    }
    csv += CsvText(key.first) + "," + CsvText(key.second) + "," + members.front()->kind + "," +
           std::to_string(members.size()) + "," + std::to_string(detected.size());
    for (const NumberColumn& column : summarised) {
      std::vector<double> values;
      for (const StateRow* row : detected) {
        if (std::isfinite(row->*column.member)) values.push_back(row->*column.member);
      }
      const Interval interval = MeanInterval95(values);
      csv += "," + CsvNumber(interval.mean) + "," + CsvNumber(interval.half_width);
    }
    csv += "\n";
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
  row.kind = joined.kind;
  row.status = "detected";
  row.message.clear();
  row.detector = fmt::format(
      "path_convergence: paths of psi_epsilon = {:g} deg from different starting states agree "
      "within {:g} in ln(1+e) and {:g} deg in psi_sigma (averaged over +-{:g} in ln p) from here "
      "on, over at least a quarter of their common range",
      joined.psi_epsilon_deg, tolerance.ln_1_plus_e, tolerance.psi_sigma_deg,
      tolerance.smoothing_lnp);
  row.psi_epsilon_deg = joined.psi_epsilon_deg;
  row.p_kpa = joined.joined_at_p_kpa;
  row.ln_1_plus_e = joined.ln_1_plus_e;
  row.e = std::expm1(joined.ln_1_plus_e);
  row.psi_sigma_deg = joined.psi_sigma_deg;
  row.q_over_p = 3.0 / std::sqrt(2.0) * std::tan(joined.psi_sigma_deg * M_PI / 180.0);
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

StateTableSummary WriteStateTable(const std::string& directory,
                                  const ConvergenceTolerance& tolerance) {
  if (!fs::exists(directory + "/study.toml")) {
    throw InputError(directory + ": not a study folder (no study.toml)");
  }
  const ConfigTable study = ConfigTable::ParseFile(directory + "/study.toml");
  const std::string ncl_case = study.GetString("ncl", "");
  StateTableSummary summary;
  summary.directory = directory;
  std::vector<StateRow> rows;
  // Paths by (replicate, kind, ψ_ε) for the convergence check.
  struct Path {
    std::string case_name;
    double start_p;
    PathSamples samples;
  };
  std::map<std::tuple<int, std::string, double>, std::vector<Path>> paths;
  std::map<std::pair<int, std::string>, std::string> parent_of;  // (replicate, case) → parent
  for (const CaseFolder& c : ListCases(directory)) {
    parent_of[{c.replicate, c.name}] = c.parent_name;
    if (!c.finished) {
      rows.push_back(MissingRow(c));
      continue;
    }
    const std::string result = c.directory + "/result.h5";
    const Hdf5File file = Hdf5File::OpenRead(result);
    const std::vector<dem::StageRecord> stages = dem::ReadStageRecords(file);
    std::optional<TimeSeries> series;
    bool any = false;
    for (const dem::StageRecord& stage : stages) {
      if (!stage.asymptote) continue;
      any = true;
      StateRow row = RowFrom(c, stage);
      if (c.termination != "completed" && row.message.empty()) row.message = c.message;
      rows.push_back(row);
      if (row.kind == "compression" || row.kind == "extension") {
        if (!series) series = TimeSeries::Read(file, "/series");
        const bool rising = row.kind == "compression";
        Path path{c.name, 0, MonotonePath(*series, stage.first_row, stage.last_row, rising)};
        if (path.samples.x.size() >= 2) {
          path.start_p = std::exp(rising ? path.samples.x.front() : path.samples.x.back());
          const double psi = std::round(row.psi_epsilon_deg * 1e6) / 1e6;
          paths[{c.replicate, row.kind, psi}].push_back(std::move(path));
        }
      }
    }
    if (!any && c.termination != "completed") rows.push_back(MissingRow(c));
  }

  // Paper Sec. 4.3: paths of one ψ_ε from successive starting states.
  std::vector<ConvergenceRow> convergence;
  for (auto& [key, group] : paths) {
    const auto& [replicate, kind, psi] = key;
    const bool rising = kind == "compression";
    std::sort(group.begin(), group.end(),
              [](const Path& a, const Path& b) { return a.start_p < b.start_p; });
    for (size_t k = 1; k < group.size(); ++k) {
      ConvergenceRow row = JoinPaths(group[k - 1].samples, group[k].samples, rising, tolerance);
      row.replicate = replicate;
      row.kind = kind;
      row.psi_epsilon_deg = psi;
      row.case_a = group[k - 1].case_name;
      row.case_b = group[k].case_name;
      summary.joined += row.status == "joined";
      summary.not_joined += row.status != "joined";
      convergence.push_back(row);
      if (row.status == "joined") rows.push_back(JoinedRow(row, tolerance));
    }
  }
  // An NCL per replicate and NCL-carrying case (the study's NCL, and the
  // NCLs of samples with another material or time step: cases with NCL
  // states at two stages or more; a case that continues an NC state to one
  // isotropic asymptote, as the rate study's ψ_ε = 0° cases do, refers to
  // its ancestor's NCL), through the stage-end states that are load-bearing
  // and reliable: detected or drifting (the detector's ψ_σ and slope tests
  // are at the noise of a small sample on a ψ_ε = 0° path), not a gas,
  // overlaps below 10 %.
  std::map<std::pair<int, std::string>, int> ncl_states;  // (replicate, case) → NCL rows
  for (const StateRow& row : rows) {
    if (row.kind == "ncl") ++ncl_states[{row.replicate, row.case_name}];
  }
  std::map<std::pair<int, std::string>, size_t> fit_of;  // (replicate, case) → summary.ncl
  for (const StateRow& row : rows) {
    const auto key = std::make_pair(row.replicate, row.case_name);
    if (row.kind != "ncl" || fit_of.count(key)) continue;
    if (ncl_states[key] < 2 && row.case_name != ncl_case) continue;
    NclFit fit;
    fit.replicate = row.replicate;
    fit.case_name = row.case_name;
    std::vector<double> x, y;
    for (const StateRow& other : rows) {
      if (other.replicate != fit.replicate || other.case_name != fit.case_name ||
          other.kind != "ncl" || (other.status != "detected" && other.status != "drifting") ||
          other.flags.find("overlap_above_10pct") != std::string::npos) {
        continue;
      }
      ++(other.status == "detected" ? fit.detected : fit.drifting);
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
    fit_of[key] = summary.ncl.size();
    summary.ncl.push_back(fit);
  }
  // Each state refers to the NCL of its nearest ancestor (or itself) that
  // has one, else to the study's NCL.
  for (StateRow& row : rows) {
    if (!(row.p_kpa > 0)) continue;
    std::string name = row.case_name.substr(0, row.case_name.find('+'));  // joined: first path
    const NclFit* fit = nullptr;
    for (int guard = 0; !name.empty() && guard < 1000; ++guard) {
      const auto it = fit_of.find({row.replicate, name});
      if (it != fit_of.end() && summary.ncl[it->second].valid()) {
        fit = &summary.ncl[it->second];
        break;
      }
      const auto up = parent_of.find({row.replicate, name});
      name = up == parent_of.end() ? "" : up->second;
    }
    if (!fit) {
      const auto it = fit_of.find({row.replicate, ncl_case});
      if (it != fit_of.end() && summary.ncl[it->second].valid()) fit = &summary.ncl[it->second];
    }
    if (!fit) continue;
    row.ncl_reference = fit->case_name;
    row.p_e_star_kpa = std::exp((fit->n - row.ln_1_plus_e) / fit->lambda);
    row.ocr = row.p_e_star_kpa / row.p_kpa;
  }
  std::string ncl_csv =
      "replicate,case,points,detected,drifting,N,lambda_star,p_min_kpa,p_max_kpa\n";
  for (const NclFit& fit : summary.ncl) {
    ncl_csv += fmt::format("{},{},{},{},{},{},{},{},{}\n", fit.replicate, fit.case_name, fit.points,
                           fit.detected, fit.drifting, CsvNumber(fit.valid() ? fit.n : kNaN),
                           CsvNumber(fit.valid() ? fit.lambda : kNaN), CsvNumber(fit.p_min_kpa),
                           CsvNumber(fit.p_max_kpa));
  }
  WriteTextFileAtomically(directory + "/ncl_fit.csv", ncl_csv);

  std::string conv_csv = fmt::format(
      "# paths of one psi_epsilon from different starting states join where ln(1+e) and "
      "psi_sigma agree within {} and {} deg at a common p from there on\n"
      "replicate,kind,psi_epsilon_deg,case_a,case_b,status,joined_at_p_kpa,ln_1_plus_e,"
      "psi_sigma_deg,overlap_from_p_kpa,overlap_to_p_kpa\n",
      tolerance.ln_1_plus_e, tolerance.psi_sigma_deg);
  for (const ConvergenceRow& row : convergence) {
    conv_csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", row.replicate, row.kind,
                            CsvNumber(row.psi_epsilon_deg), row.case_a, row.case_b, row.status,
                            CsvNumber(row.joined_at_p_kpa), CsvNumber(row.ln_1_plus_e),
                            CsvNumber(row.psi_sigma_deg), CsvNumber(row.overlap_from_p_kpa),
                            CsvNumber(row.overlap_to_p_kpa));
  }
  WriteTextFileAtomically(directory + "/path_convergence.csv", conv_csv);

  for (const StateRow& row : rows) ++summary.counts[row.kind][row.status];
  WriteRows(directory, rows, summary.ncl);
  WriteSummary(directory, rows);
  if (const std::optional<RateStudy> rate = WriteRateStudy(directory, rows)) {
    summary.rate = rate->Text();
  }
  return summary;
}

std::vector<StateRow> ReadStateTable(const std::string& directory) {
  const Hdf5File file = Hdf5File::OpenRead(directory + "/" + table::kFileName);
  const std::vector<int64_t> replicates = file.ReadInts(std::string(table::kStatesGroup) + "/" + table::kColumnReplicate);
  std::vector<StateRow> rows(replicates.size());
  for (size_t k = 0; k < rows.size(); ++k) rows[k].replicate = static_cast<int>(replicates[k]);
  for (const NumberColumn& column : kNumberColumns) {
    const std::vector<double> values = file.ReadDoubles(std::string(table::kStatesGroup) + "/" + column.name);
    for (size_t k = 0; k < rows.size() && k < values.size(); ++k) rows[k].*column.member = values[k];
  }
  for (const TextColumn& column : kTextColumns) {
    const std::vector<std::string> values = file.ReadStrings(std::string(table::kStatesGroup) + "/" + column.name);
    for (size_t k = 0; k < rows.size() && k < values.size(); ++k) rows[k].*column.member = values[k];
  }
  return rows;
}

std::string StateTableSummary::Text() const {
  std::string text = "asymptotic states (" + directory + "/asymptotic_states.csv):\n";
  for (const auto& [kind, statuses] : counts) {
    text += fmt::format("  {:<12}", kind);
    for (const auto& [status, count] : statuses) text += fmt::format(" {} {}", count, status);
    text += "\n";
  }
  for (const NclFit& fit : ncl) {
    text += fit.valid()
                ? fmt::format("  NCL r{} {}: N = {:.4f}, lambda* = {:.4f} through {} states "
                              "({} detected, {} drifting), {:.4g}-{:.4g} kPa\n",
                              fit.replicate, fit.case_name, fit.n, fit.lambda, fit.points, fit.detected,
                              fit.drifting, fit.p_min_kpa, fit.p_max_kpa)
                : fmt::format("  NCL r{} {}: not determined ({} usable states)\n",
                              fit.replicate, fit.case_name, fit.points);
  }
  text += fmt::format("  path convergence: {} pairs joined, {} not\n", joined, not_joined);
  return text + rate;
}

}  // namespace granasym::study
