#include "study/state_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <set>
#include <sstream>

#include "common/hdf5_file.h"
#include "common/state_measures.h"
#include "common/text_file.h"
#include "common/time_series.h"
#include "dem/run_record.h"
#include "dem/run_record_names.h"
#include "dem/stage_validity.h"
#include "study/case_record.h"
#include "study/study_folder.h"

namespace granasym::study {
namespace {

// Two compression paths approaching the line ln(1+e) = 1 − 0.05 ln p and
// ψ_σ = 20° from different starts: each deviates by an amount that decays
// with ln p from its own start.
PathSamples Path(double start_lnp, double offset, double decay) {
  PathSamples path;
  for (double x = start_lnp; x <= 8.0; x += 0.01) {
    const double gap = offset * std::exp(-(x - start_lnp) / decay);
    path.x.push_back(x);
    path.y.push_back(1.0 - 0.05 * x + gap);
    path.psi.push_back(20.0 - 400.0 * gap);
  }
  return path;
}

TEST(PathConvergence, PathsThatApproachOneLineJoinWhereTheirGapFallsBelowTheTolerance) {
  const PathSamples low = Path(1.0, 0.02, 0.5), high = Path(3.0, -0.02, 0.5);
  ConvergenceTolerance tolerance;
  tolerance.psi_sigma_deg = 1.0;
  tolerance.smoothing_lnp = 0.0;  // exact paths: no averaging
  const ConvergenceRow row = JoinPaths(low, high, tolerance);
  ASSERT_EQ(row.status, "joined");
  // The ψ_σ gap 400 (g_low + |g_high|) < 1 deg decides (the ln(1+e) gap is
  // within 0.005 from x = 3 + 0.5 ln 4 = 3.69): |g_high| = 0.02 exp(−(x−3)/0.5)
  // falls below 1/400 at x = 3 + 0.5 ln 8 = 4.04 (g_low is below 1e-4 there),
  // and the grid over [3, 8] has a point every 0.128.
  EXPECT_NEAR(std::log(row.joined_at_p_kpa), 4.1, 0.15);
  EXPECT_NEAR(row.psi_sigma_deg, 20.0, 1.0);
  EXPECT_NEAR(row.ln_1_plus_e, 1.0 - 0.05 * std::log(row.joined_at_p_kpa), 0.005);
}

TEST(PathConvergence, ParallelPathsThatStayApartDoNotJoin) {
  const PathSamples a = Path(1.0, 0.0, 1.0);
  PathSamples b = Path(2.0, 0.0, 1.0);
  for (double& v : b.y) v += 0.02;  // a parallel line 0.02 above
  EXPECT_EQ(JoinPaths(a, b, {}).status, "not_joined");
  const PathSamples c = Path(1.0, 0.0, 1.0);
  PathSamples d;
  d.x = {9.0, 10.0};
  d.y = {0.5, 0.45};
  d.psi = {20.0, 20.0};
  EXPECT_EQ(JoinPaths(c, d, {}).status, "no_overlap");
}

// Two extension paths of the paper's rate: each falls steeply from its NC
// state and then runs nearly vertically in ln(1+e)–ln p (a dense flow, p
// about 1 kPa while ln(1+e) rises), from different starting void ratios; on
// a common ln(1+e) they agree once both are in the flow. At a common ln p
// they never would (p barely moves along the flow).
PathSamples Flow(double start_v, double start_lnp) {
  PathSamples path;
  for (double x = start_v; x <= 0.75; x += 0.0005) {
    const double fall = std::max(0.0, 1.0 - (x - start_v) / 0.02);  // the fall: 0.02 of ln(1+e)
    path.x.push_back(x);
    path.y.push_back(fall * start_lnp + 0.1 * std::sin(900.0 * x) - 0.5 * (x - 0.5));
    path.psi.push_back(40.0 - 30.0 * fall);
  }
  return path;
}

TEST(PathConvergence, ExtensionFlowsJoinAtACommonVoidRatio) {
  const PathSamples from500 = Flow(0.530, std::log(500.0));
  const PathSamples from1000 = Flow(0.511, std::log(1000.0));
  const ConvergenceRow row = JoinExtensionPaths(from500, from1000, {});
  ASSERT_EQ(row.status, "joined");
  // The path from 500 kPa is in its flow from ln(1+e) = 0.55 on.
  EXPECT_NEAR(row.ln_1_plus_e, 0.55, 0.01);
  EXPECT_NEAR(row.psi_sigma_deg, 40.0, 2.0);
  EXPECT_NEAR(std::log(row.joined_at_p_kpa), -0.5 * (row.ln_1_plus_e - 0.5), 0.1);
  EXPECT_GT(row.overlap_from_p_kpa, row.overlap_to_p_kpa);  // p falls along the overlap
  // Flows of different ψ_ε lie apart in ln p (OCR grows with ψ_ε): not joined.
  PathSamples lower = from500;
  for (double& y : lower.y) y -= 0.6;
  EXPECT_EQ(JoinExtensionPaths(lower, from1000, {}).status, "not_joined");
}

TEST(Replicates, MeanAndStudentIntervalOfTheMean) {
  // n = 3: mean 2, s = 1, t(0.975, 2) = 4.303: half-width 4.303 / sqrt(3).
  const Interval three = MeanInterval95({1.0, 2.0, 3.0});
  EXPECT_DOUBLE_EQ(three.mean, 2.0);
  EXPECT_NEAR(three.half_width, 4.303 / std::sqrt(3.0), 1e-12);
  // n = 2: t(0.975, 1) = 12.706, s = sqrt(2) * 0.5.
  const Interval two = MeanInterval95({10.0, 11.0});
  EXPECT_NEAR(two.half_width, 12.706 * std::sqrt(0.5) / std::sqrt(2.0), 1e-12);
  EXPECT_TRUE(std::isnan(MeanInterval95({5.0}).half_width));
  EXPECT_TRUE(std::isnan(MeanInterval95({}).mean));
}

// A study of three replicates written without the DEM: per replicate an NCL
// case (three ψ_ε = 0° stages) and two ψ_ε = 30° paths from 20 and 100 kPa
// that approach one line (as Path above, in strain), each stage a series of
// rows every 0.002 of strain and a record whose detector drifted.
namespace fs = std::filesystem;

struct SyntheticStage {
  std::string name;
  double psi_epsilon_deg, start_log_p, length;
  std::function<double(double log_p, double strain)> log_volume, psi_sigma_deg;
  // The rate at the asymptote and the stage's validity flags.
  double inertial_number_dmin = 0, inertial_number_dmax = 0;
  std::vector<dem::ValidityFlag> flags = {};
};

TimeSeries EmptySeries() {
  namespace r = dem::record;
  return TimeSeries({{r::kColumnMeanStress, "kPa", ""},
                     {r::kColumnVoidRatio, "1", ""},
                     {r::kColumnPsiSigma, "deg", ""},
                     {r::kColumnMechanicalCoordination, "1", ""},
                     {r::kColumnAxialStrain, "1", ""},
                     {r::kColumnRadialStrain, "1", ""},
                     {r::kColumnTime, "s", ""}});
}

// Appends a stage's rows (ln p rising by 3 per unit strain) and returns its record.
dem::StageRecord AddStage(const SyntheticStage& stage, TimeSeries* series) {
  const AxisymmetricRate unit = AxisymmetricRate::FromAngle(stage.psi_epsilon_deg * kDegree, 1.0);
  dem::StageRecord record;
  record.name = stage.name;
  record.type = "strain_path";
  record.first_row = static_cast<int64_t>(series->rows());
  const double eps_a = series->rows() ? series->Last(dem::record::kColumnAxialStrain) : 0.0;
  const double eps_r = series->rows() ? series->Last(dem::record::kColumnRadialStrain) : 0.0;
  double log_p = stage.start_log_p, e = 0, psi = 0;
  for (double s = 0; s <= stage.length + 1e-9; s += 0.002) {
    log_p = stage.start_log_p + 3.0 * s;
    e = std::expm1(stage.log_volume(log_p, s));
    psi = stage.psi_sigma_deg(log_p, s);
    series->AddRow(
        {std::exp(log_p), e, psi, 4.5, eps_a + unit.axial * s, eps_r + unit.radial * s, s / 167.0});
  }
  record.last_row = static_cast<int64_t>(series->rows()) - 1;
  dem::AsymptoteRecord a;
  a.path_kind = dem::PathKind::kCompression;
  a.criterion = dem::AsymptoteCriterion::For(a.path_kind);
  a.status = dem::AsymptoteStatus::kDrifting;
  a.psi_epsilon_deg = stage.psi_epsilon_deg;
  a.mean_stress_kpa = std::exp(log_p);
  a.void_ratio = e;
  a.psi_sigma_deg = psi;
  a.mechanical_coordination = 4.5;
  a.window_strain = 0.3;
  a.inertial_number_dmin = stage.inertial_number_dmin;
  a.inertial_number_dmax = stage.inertial_number_dmax;
  record.validity.flags = stage.flags;
  record.asymptote = a;
  record.asymptote_criterion = a.criterion.Describe();
  record.stop_reason = "stage done";
  return record;
}

// `inertial_number` > 0: each stage is a strain path at that inertial
// number (the rate attributes of dem::record); 0: no rate recorded.
void WriteCase(const std::string& study, int replicate, const std::string& name,
               const std::string& parent, const std::vector<SyntheticStage>& stages,
               double inertial_number = 0) {
  CaseRecord record;
  record.id = "r" + std::to_string(replicate) + "/" + name;
  record.name = name;
  record.replicate = replicate;
  record.key = "key-" + record.id;
  record.parent = parent.empty() ? "" : "r" + std::to_string(replicate) + "/" + parent;
  record.run = name;
  const std::string folder = study + "/cases/" + record.id;
  fs::create_directories(folder);
  record.Write(folder);
  DoneRecord done;
  done.key = record.key;
  done.termination = dem::Termination::kCompleted;
  WriteDone(folder, done);
  TimeSeries series = EmptySeries();
  std::vector<dem::StageRecord> records;
  for (const SyntheticStage& stage : stages) records.push_back(AddStage(stage, &series));
  Hdf5File file = Hdf5File::CreateAtomic(folder + "/result.h5");
  dem::RunSummary summary;
  summary.termination = dem::Termination::kCompleted;
  dem::WriteSummary(file, summary, {});
  series.Write(file, dem::record::kSeries);
  dem::WriteStageRecords(file, records, {}, 1);
  for (size_t k = 0; inertial_number > 0 && k < stages.size(); ++k) {
    const std::string group = dem::StageGroup(k);
    file.SetAttribute(group, dem::record::kStageStretchingRate, 5000.0);
    file.SetAttribute(group, dem::record::kStageRateRule, "inertial");
    file.SetAttribute(group, dem::record::kStageRateInertialNumber, inertial_number);
  }
  file.Commit();
}

// `with_rate`: the path from 20 kPa at I(d_min) 0.002, I(d_max) 0.02 and
// flagged rate_affected, the one from 100 kPa at 0.0005, 0.005 with an
// overlap above 2 %.
// `two_rates`: the two starts' paths at different inertial numbers (1e-3
// from 20 kPa, 3e-3 from 100 kPa), so that they are no pair.
std::string SyntheticStudy(const std::string& name, bool with_rate = false,
                           bool two_rates = false) {
  const fs::path dir = fs::temp_directory_path() / "granasym_tests" / "state_table" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  WriteTextFileAtomically((dir / "study.toml").string(), "scale = \"small\"\nncl = \"ncl\"\n");
  for (int k = 1; k <= 3; ++k) {
    const double offset = 0.002 * (k - 2), phase = 2 * kPi * k / 3.0;
    auto ncl = [offset](double log_p, double) { return 0.7 + offset - 0.05 * log_p; };
    auto noise = [phase](double, double s) { return 0.3 * std::sin(2 * kPi * s / 0.5 + phase); };
    std::vector<SyntheticStage> stages;
    for (int j = 0; j < 3; ++j) {
      stages.push_back({"p" + std::to_string(j), 0.0, std::log(10.0) + 1.2 * j, 0.4, ncl, noise});
    }
    WriteCase(dir.string(), k, "ncl", "", stages);
    for (const double start : {20.0, 100.0}) {
      const double sign = start < 50 ? 1.0 : -1.0, log_p0 = std::log(start);
      auto gap = [sign, log_p0](double log_p) {
        return sign * 0.02 * std::exp(-2 * (log_p - log_p0));
      };
      SyntheticStage path{
          "psi30",
          30.0,
          log_p0,
          1.2,
          [gap, offset](double log_p, double) { return 0.6 + offset - 0.05 * log_p + gap(log_p); },
          [gap, noise](double log_p, double s) {
            return 20.0 - 400.0 * gap(log_p) + noise(log_p, s);
          }};
      if (with_rate) {
        const bool slow = start > 50;
        path.inertial_number_dmin = slow ? 0.0005 : 0.002;
        path.inertial_number_dmax = slow ? 0.005 : 0.02;
        path.flags = {slow ? dem::ValidityFlag::kOverlapAbove2Pct
                           : dem::ValidityFlag::kRateAffected};
      }
      WriteCase(dir.string(), k, "nc" + std::to_string(static_cast<int>(start)) + "_psi30", "ncl",
                {path}, two_rates ? (start < 50 ? 1e-3 : 3e-3) : 0.0);
    }
  }
  return dir.string();
}

const StateRow* Find(const std::vector<StateRow>& rows, const std::string& case_id,
                     const std::string& stage) {
  for (const StateRow& row : rows) {
    if (row.case_id == case_id && row.stage == stage) return &row;
  }
  return nullptr;
}

TEST(EnsembleRows, EachStageOfSeveralReplicatesGetsAnEnsembleRowMarkedAsSuch) {
  const std::string dir = SyntheticStudy("ensemble_rows");
  const StateTableSummary summary = WriteStateTable(dir);
  const std::vector<StateRow> rows = ReadStateTable(dir);
  const StateRow* mean = Find(rows, "mean/ncl", "p2");
  ASSERT_NE(mean, nullptr);
  EXPECT_EQ(mean->replicate, 0);
  EXPECT_EQ(mean->source, TableSource::kEnsemble);
  EXPECT_EQ(mean->case_name, "ncl");
  EXPECT_EQ(mean->kind, TableKind::kNcl);
  EXPECT_EQ(mean->status, TableStatus::kDetected) << mean->message;
  EXPECT_NE(mean->message.find("ensemble mean of 3 replicates"), std::string::npos);
  // The replicates' offsets of ±0.002 in ln(1+e) average out.
  EXPECT_NEAR(mean->ln_1_plus_e, 0.7 - 0.05 * std::log(mean->p_kpa), 1e-9);
  // OCR and p_e* against the NCL through the ensemble rows (replicate 0).
  EXPECT_EQ(mean->ncl_reference, "ncl");
  EXPECT_NEAR(mean->ocr, 1.0, 1e-6);
  const StateRow* psi30 = Find(rows, "mean/nc100_psi30", "psi30");
  ASSERT_NE(psi30, nullptr);
  EXPECT_EQ(psi30->source, TableSource::kEnsemble);
  EXPECT_EQ(Find(rows, "r2/ncl", "p2")->source, TableSource::kReplicate);
  int ensemble = 0, joined = 0;
  for (const StateRow& row : rows) {
    ensemble += row.source == TableSource::kEnsemble;
    if (row.source == TableSource::kJoined) {
      ++joined;
      EXPECT_EQ(row.stage, table::kStageJoined);
      EXPECT_GE(row.replicate, 1);
    }
  }
  EXPECT_EQ(ensemble, 5);  // three NCL stages, two ψ_ε = 30° paths
  EXPECT_EQ(joined, 3);    // one pair per replicate, none of the means
  EXPECT_EQ(WithoutEnsembleRows(rows).size(), rows.size() - 5);
  // The summary counts them apart.
  EXPECT_EQ(summary.ensemble_counts.at("ncl").at("detected"), 3);
  EXPECT_EQ(summary.counts.at("ncl").at("drifting"), 9);
  EXPECT_NE(summary.Text().find("ensemble means"), std::string::npos) << summary.Text();
  EXPECT_NE(summary.Text().find("NCL mean ncl"), std::string::npos) << summary.Text();
}

TEST(EnsembleRows, TheSourceColumnRoundTripsAndOlderTablesReadWithoutIt) {
  const std::string dir = SyntheticStudy("source_column");
  WriteStateTable(dir);
  const std::vector<StateRow> rows = ReadStateTable(dir);
  // The CSV names each row's source in its column.
  const std::string csv = ReadTextFile(dir + "/asymptotic_states.csv");
  const std::string header = csv.substr(0, csv.find('\n'));
  EXPECT_NE(header.find(",held_before_end,source,ncl_reference,"), std::string::npos) << header;
  std::set<std::string> sources;
  size_t line = csv.find('\n') + 1, index = 0;
  const size_t column =
      static_cast<size_t>(std::count(
          header.begin(), header.begin() + static_cast<long>(header.find(",source,")), ',')) +
      1;
  for (; line < csv.size(); line = csv.find('\n', line) + 1, ++index) {
    size_t field = line;
    for (size_t c = 0; c < column; ++c) field = csv.find(',', field) + 1;
    const std::string source = csv.substr(field, csv.find(',', field) - field);
    sources.insert(source);
    ASSERT_LT(index, rows.size());
    EXPECT_EQ(source, ToString(rows[index].source)) << rows[index].case_id;
  }
  EXPECT_EQ(sources, (std::set<std::string>{"replicate", "ensemble", "joined"}));
  // The same table without the column (written before it): ensemble rows
  // cannot be in it; the joined rows are known by their stage.
  const std::string h5 = dir + "/" + table::kFileName;
  {
    fs::create_directories(dir + "/old");
    const Hdf5File file = Hdf5File::OpenRead(h5);
    Hdf5File old = Hdf5File::CreateAtomic(dir + "/old/" + table::kFileName);
    old.CreateGroup(table::kStatesGroup);
    const std::set<std::string> ints = {table::kColumnReplicate, table::kColumnHeldBeforeEnd};
    const std::set<std::string> texts = {
        table::kColumnKind,     table::kColumnStatus,  table::kColumnCase,
        table::kColumnCaseName, table::kColumnStage,   table::kColumnNclReference,
        table::kColumnRun,      table::kColumnFigures, table::kColumnFlags,
        table::kColumnDetector, table::kColumnMessage};
    for (const std::string& name : file.List(table::kStatesGroup)) {
      const std::string path = std::string(table::kStatesGroup) + "/" + name;
      if (name == table::kColumnSource) continue;
      if (ints.count(name)) {
        old.WriteInts(path, file.ReadInts(path));
      } else if (texts.count(name)) {
        old.WriteStrings(path, file.ReadStrings(path));
      } else {
        old.WriteDoubles(path, file.ReadDoubles(path), "1");
      }
    }
    old.Commit();
  }
  const std::vector<StateRow> older = ReadStateTable(dir + "/old");
  ASSERT_EQ(older.size(), rows.size());
  for (size_t k = 0; k < rows.size(); ++k) {
    const TableSource expected =
        rows[k].stage == table::kStageJoined ? TableSource::kJoined : TableSource::kReplicate;
    EXPECT_EQ(older[k].source, expected) << rows[k].case_id;
    EXPECT_EQ(older[k].case_id, rows[k].case_id);
  }
}

TEST(EnsembleRows, TheSummaryNclFitsAndPathConvergenceCountReplicatesOnly) {
  const std::string dir = SyntheticStudy("replicates_only");
  const StateTableSummary summary = WriteStateTable(dir);
  // The summary: three replicates per stage, the ensemble row's state beside.
  const std::string table = ReadTextFile(dir + "/asymptotic_states_summary.csv");
  EXPECT_NE(table.find(",ensemble_status,ensemble_psi_sigma_deg,ensemble_ln_1_plus_e\n"),
            std::string::npos)
      << table.substr(0, 400);
  EXPECT_NE(table.find("\nncl,p2,ncl,3,0,"), std::string::npos) << table;
  EXPECT_NE(table.find("\nnc20_psi30,psi30,compression,3,0,"), std::string::npos) << table;
  EXPECT_EQ(table.find("\nncl,p2,ncl,4,"), std::string::npos) << table;
  const size_t ncl_line = table.find("\nncl,p2,");
  const std::string line =
      table.substr(ncl_line + 1, table.find('\n', ncl_line + 1) - ncl_line - 1);
  EXPECT_NE(line.find(",detected,"), std::string::npos) << line;
  // The NCL of each replicate through its own three states; the ensemble's
  // apart, as replicate 0.
  ASSERT_EQ(summary.ncl.size(), 4u);
  for (const NclFit& fit : summary.ncl) {
    EXPECT_EQ(fit.points, 3) << fit.replicate;
    EXPECT_NEAR(fit.lambda, 0.05, 1e-3) << fit.replicate;
    if (fit.replicate == 0) {
      EXPECT_NEAR(fit.n, 0.7, 1e-3);
    }
  }
  // Path convergence: one pair per replicate.
  const std::string convergence = ReadTextFile(dir + "/path_convergence.csv");
  EXPECT_EQ(convergence.find("\n0,"), std::string::npos) << convergence;
  for (const char* replicate :
       {"\n1,compression,30,", "\n2,compression,30,", "\n3,compression,30,"}) {
    EXPECT_NE(convergence.find(replicate), std::string::npos) << convergence;
  }
  EXPECT_EQ(summary.joined, 3);
}

// Issue 36 §2: a joined state carries the inertial numbers and flags of the
// rows of the paths it joins (the larger I, every flag of either), in the
// table and its CSV, so that selections by flag or by I treat it as its paths.
TEST(JoinedRows, CarryTheLargerInertialNumbersAndTheFlagsOfThePathsTheyJoin) {
  const std::string dir = SyntheticStudy("joined_rate", true);
  WriteStateTable(dir);
  int joined = 0;
  for (const StateRow& row : ReadStateTable(dir)) {
    if (row.source != TableSource::kJoined) continue;
    ++joined;
    EXPECT_EQ(row.case_name, "nc20_psi30+nc100_psi30");
    EXPECT_DOUBLE_EQ(row.inertial_number_dmin, 0.002);
    EXPECT_DOUBLE_EQ(row.inertial_number_dmax, 0.02);
    EXPECT_EQ(row.flags, "rate_affected;overlap_above_2pct");
  }
  EXPECT_EQ(joined, 3);
  const std::string csv = ReadTextFile(dir + "/asymptotic_states.csv");
  EXPECT_NE(csv.find("rate_affected;overlap_above_2pct"), std::string::npos);
}

// Paths of one ψ_ε join only at one rate (and of one material): a rate
// sweep's paths are no pair, however close they run.
TEST(JoinedRows, PathsAtTwoRatesAreNoPair) {
  // The control: the same paths at one rate join, once per replicate.
  EXPECT_EQ(WriteStateTable(SyntheticStudy("one_rate", false, false)).joined, 3);
  const std::string dir = SyntheticStudy("two_rates", false, true);
  const StateTableSummary summary = WriteStateTable(dir);
  EXPECT_EQ(summary.joined + summary.not_joined, 0);
  for (const StateRow& row : ReadStateTable(dir)) EXPECT_NE(row.source, TableSource::kJoined);
  // path_convergence.csv: its comments and header, no pair.
  std::istringstream csv(ReadTextFile(dir + "/path_convergence.csv"));
  int data_lines = 0;
  for (std::string line; std::getline(csv, line);) {
    data_lines += !line.empty() && line[0] != '#' && line.rfind("replicate,", 0) != 0;
  }
  EXPECT_EQ(data_lines, 0);
}

}  // namespace
}  // namespace granasym::study
