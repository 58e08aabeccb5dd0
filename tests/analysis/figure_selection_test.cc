// Which states and paths the figures take (issue 35 §1–§2): samples by the
// cases' own results, statuses, the legends' numeric order, axes from the
// valid rows, hover labels; and the figure settings (study/figure_settings.h).
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "analysis/figure_context.h"
#include "analysis/figure_families.h"
#include "common/config.h"
#include "common/error.h"
#include "common/text_file.h"
#include "study/programme.h"

namespace granasym::analysis::figures {
namespace {

namespace fs = std::filesystem;

fs::path TempDir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("granasym_figure_selection_" + std::to_string(getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A finished case: a parent stage (for its start) and a path of n rows.
CaseData Case(const std::string& name, double friction, const std::string& parent = "",
              const std::string& figures = "") {
  CaseData c;
  c.name = name;
  c.finished = true;
  c.friction = friction;
  c.time_step = 1e-7;
  c.parent_name = parent;
  c.figures = study::FigureSet::Parse(figures, "test", "figures");
  return c;
}

// An NCL case with one ψ_ε = 0° stage per target p.
CaseData Ncl(const std::string& name, double friction, const std::vector<double>& targets) {
  CaseData c = Case(name, friction);
  for (double p : targets) {
    dem::StageRecord stage;
    stage.name = "p" + std::to_string(static_cast<int>(p));
    stage.validity.final_mean_stress_kpa = p * 1.001;  // the stop overshoots slightly
    c.stages.push_back(stage);
    c.stage_psi_epsilon.push_back(0);
    c.stage_radial_stress.push_back(NAN);
  }
  c.path.p = targets;
  c.path.ln_v.assign(targets.size(), 0.55);
  return c;
}

// A ψ_ε = 90° path from the NCL stage `start`: p falls from the start to
// `p_end` (below the 0.5 kPa floor for a gas).
CaseData Path90(const std::string& name, double friction, double start, double p_end,
                const std::string& figures = "10") {
  CaseData c = Case(name, friction, "ncl", figures);
  c.parent_stage = "p" + std::to_string(static_cast<int>(start));
  dem::StageRecord stage;
  stage.name = "shear";
  c.stages.push_back(stage);
  c.stage_psi_epsilon.push_back(90);
  c.stage_radial_stress.push_back(NAN);
  for (int k = 0; k <= 20; ++k) {
    const double p = start * std::pow(p_end / start, k / 20.0);
    c.path.p.push_back(p);
    c.path.ln_v.push_back(0.6 - 0.01 * std::log(start));
    c.path.psi_sigma.push_back(25.0 * k / 20);
    c.path.psi_epsilon.push_back(90);
    c.path.eps_s.push_back(0.01 * k);
    c.path.q.push_back(p * 0.9 * k / 20);
    c.path.eps_a.push_back(0.01 * k);
    c.path.eps_r.push_back(-0.005 * k);
  }
  return c;
}

StateRow Row(const std::string& name, TableKind kind, TableStatus status, double p) {
  StateRow row;
  row.case_name = name;
  row.stage = "shear";
  row.kind = kind;
  row.status = status;
  row.p_kpa = p;
  row.ln_1_plus_e = 0.55;
  row.e = std::expm1(0.55);
  row.psi_sigma_deg = 24;
  row.psi_epsilon_deg = kind == TableKind::kCsl ? 90 : 0;
  row.q_over_p = 0.9;
  return row;
}

// The study of the tests: the NCL at φ = 0.5 rad and its 90° paths, and a
// frictionless NCL with one 90° path of its own.
Context Study(const fs::path& data) {
  Context ctx;
  ctx.data = data.string();
  ctx.study_ncl = "ncl";
  ctx.cases.push_back(Ncl("ncl", 0.5, {20, 100, 200, 1000}));
  ctx.cases.push_back(Ncl("ncl_phi0", 0.0, {100}));
  // Added in text order, which is not the numeric order of their starts.
  ctx.cases.push_back(Path90("nc1000_psi90", 0.5, 1000, 300));
  ctx.cases.push_back(Path90("nc100_psi90", 0.5, 100, 30));
  ctx.cases.push_back(Path90("nc200_psi90", 0.5, 200, 60));
  ctx.cases.push_back(Path90("nc20_psi90", 0.5, 20, 1e-4));  // a gas below the floor
  CaseData phi0 = Path90("phi0_nc100_psi90", 0.0, 100, 10, "20");
  phi0.parent_name = "ncl_phi0";
  ctx.cases.push_back(phi0);
  ctx.states = {Row("nc100_psi90", TableKind::kCsl, TableStatus::kDetected, 30),
                Row("nc200_psi90", TableKind::kCsl, TableStatus::kDrifting, 60),
                Row("nc1000_psi90", TableKind::kCsl, TableStatus::kDetected, 300),
                Row("nc20_psi90", TableKind::kCsl, TableStatus::kGas, 1e-4),
                Row("phi0_nc100_psi90", TableKind::kCsl, TableStatus::kDetected, 10)};
  ctx.ncl_fits[{1, "ncl"}] = NclLine{0.7, 0.025};
  ClassifySamples(&ctx);
  return ctx;
}

std::string Variable(const FigureSpec& spec, const std::string& name) {
  for (const auto& [key, value] : spec.variables) {
    if (key == name) return value;
  }
  ADD_FAILURE() << "no variable " << name;
  return "";
}

TEST(FigureSelection, SamplesComeFromTheCasesOwnResults) {
  const Context ctx = Study(TempDir("samples"));
  EXPECT_EQ(ctx.Case(1, "nc100_psi90")->sample, Sample::kMain);
  EXPECT_EQ(ctx.Case(1, "phi0_nc100_psi90")->sample, Sample::kOtherFriction);
  EXPECT_EQ(ctx.main_friction, 0.5);
}

TEST(FigureSelection, AFrictionlessStateNeverReachesTheStudysOwnFigures) {
  const Context ctx = Study(TempDir("phi0"));
  StateSelection csl;
  csl.kinds = {TableKind::kCsl};
  std::vector<std::string> names;
  for (const StateRow* row : ctx.Select(csl)) names.push_back(row->case_name);
  EXPECT_EQ(names, (std::vector<std::string>{"nc100_psi90", "nc200_psi90", "nc1000_psi90"}));
  csl.drifting = false;
  EXPECT_EQ(ctx.Select(csl).size(), 2u);  // the drifting one left out, the gas always
  StateSelection other = csl;
  other.sample = Sample::kOtherFriction;
  ASSERT_EQ(ctx.Select(other).size(), 1u);
  EXPECT_EQ(ctx.Select(other).front()->case_name, "phi0_nc100_psi90");
  EXPECT_NE(csl.Describe(ctx).find("φ = 0.5 rad"), std::string::npos) << csl.Describe(ctx);
}

TEST(FigureSelection, TheSummaryFigureHoldsOnlyTheStudysOwnStatesWithAHoverLabelEach) {
  const fs::path data = TempDir("fig16");
  const Context ctx = Study(data);
  ASSERT_TRUE(Fig16(ctx).not_drawn.empty());
  const std::string text = ReadTextFile((data / "fig16_states.tsv").string());
  EXPECT_EQ(text.find("phi0"), std::string::npos) << text;
  // One labelled row per usable state of the study's sample.
  int rows = 0;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.find("(replicate 1)") != std::string::npos) ++rows;
  }
  EXPECT_EQ(rows, 3);
}

TEST(FigureSelection, LegendsAreInNumericOrderWithRoundedStarts) {
  const Context ctx = Study(TempDir("legend"));
  const FigureSpec spec = PathFamily(ctx, {"10", "fig10_csl_nc", "t", "w", {}, true});
  ASSERT_TRUE(spec.not_drawn.empty()) << spec.not_drawn;
  // One direction: one colour per start, 20 < 100 < 200 < 1000 (not text order),
  // and the stops' overshoot (1001 kPa) rounded away.
  EXPECT_EQ(Variable(spec, "colour_titles"),
            "'\"NC 20 kPa\" \"NC 100 kPa\" \"NC 200 kPa\" \"NC 1000 kPa\"'");
  EXPECT_EQ(Variable(spec, "path_colours"), "'1 2 3 4 '");
  EXPECT_EQ(Rounded(0.99), 1.0);
  EXPECT_EQ(Rounded(1001), 1000.0);
  EXPECT_EQ(Rounded(47), 47.0);  // not within 5 % of 50
}

TEST(FigureSelection, PathsAtTwoRatesFromOneStartAreToldApart) {
  // A rate sweep: the same direction from the same starts at two inertial
  // numbers. Without the rate in the start's label both rates of a start
  // would share a colour and a legend entry.
  Context ctx;
  ctx.data = TempDir("rates").string();
  ctx.study_ncl = "ncl";
  ctx.cases.push_back(Ncl("ncl", 0.5, {100, 1000}));
  for (const auto& [start, rate] : std::vector<std::pair<double, std::string>>{
           {1000, "0.003"}, {100, "0.001"}, {1000, "0.001"}, {100, "0.003"}}) {
    CaseData c = Path90(fmt::format("nc{}_psi90_I{}", start, rate), 0.5, start, start / 10);
    c.rate_label = "I* = " + rate;
    ctx.cases.push_back(c);
  }
  ClassifySamples(&ctx);
  const FigureSpec spec = PathFamily(ctx, {"10", "fig10_csl_nc", "t", "w", {}, true});
  ASSERT_TRUE(spec.not_drawn.empty()) << spec.not_drawn;
  EXPECT_EQ(Variable(spec, "colour_titles"),
            "'\"NC 100 kPa, I* = 0.001\" \"NC 100 kPa, I* = 0.003\" "
            "\"NC 1000 kPa, I* = 0.001\" \"NC 1000 kPa, I* = 0.003\"'");
  // One rate: the start's label alone.
  Context one = Study(TempDir("one_rate"));
  for (CaseData& c : one.cases) c.rate_label = "I* = 0.001";
  const FigureSpec plain = PathFamily(one, {"10", "fig10_csl_nc", "t", "w", {}, true});
  EXPECT_EQ(Variable(plain, "colour_titles"),
            "'\"NC 20 kPa\" \"NC 100 kPa\" \"NC 200 kPa\" \"NC 1000 kPa\"'");
}

TEST(FigureSelection, AxesComeFromTheValidRowsNotFromAGasTail) {
  const fs::path data = TempDir("axes");
  const Context ctx = Study(data);
  const FigureSpec spec = PathFamily(ctx, {"10", "fig10_csl_nc", "t", "w", {}, true});
  // nc20_psi90 falls to 1e-4 kPa: its tail is drawn faint, the axis stays near the 0.5 kPa floor.
  EXPECT_GT(std::stod(Variable(spec, "p_lo")), 0.2);
  EXPECT_EQ(Variable(spec, "n_tails"), "1");
  const std::string marks = ReadTextFile((data / "fig10_csl_nc_states.tsv").string());
  EXPECT_EQ(marks.find("nc20_psi90"), std::string::npos) << "a gas is no asymptotic state";
  // The NCL and the CSL fit (3 detected critical states are needed: here 2, so the NCL only).
  EXPECT_EQ(Variable(spec, "n_lines"), "1");
}

TEST(FigureSettings, ReadsEveryKeyAndRefusesUnknownOnes) {
  const ConfigTable file = ConfigTable::ParseString(
      "[figures]\nlevels = [0.52, 0.56]\nfig18_level = 0.55\ncases = [\"nc*\"]\n"
      "exclude_cases = [\"*_psi150\"]\nonly = [\"10\"]\nmodels = [\"hypoplastic_clay\"]\n"
      "replicates = true\n",
      "p.toml");
  const study::FigureSettings s = study::FigureSettings::FromConfig(file.GetTable("figures"));
  EXPECT_EQ(s.levels, (std::vector<double>{0.52, 0.56}));
  EXPECT_EQ(s.fig18_level.value_or(0), 0.55);
  EXPECT_TRUE(s.IncludesCase("nc100_psi90"));
  EXPECT_FALSE(s.IncludesCase("oc20_psi90"));
  EXPECT_FALSE(s.IncludesCase("nc100_psi150"));
  EXPECT_TRUE(s.IncludesFigure("fig10_csl_nc", "10"));
  EXPECT_FALSE(s.IncludesFigure("fig16_asymptotic_states", "16"));
  EXPECT_TRUE(s.Overlays("hypoplastic_clay"));
  EXPECT_FALSE(s.Overlays("hypoplastic_sand"));
  EXPECT_TRUE(s.replicates);
  // Its text round-trips.
  const ConfigTable again = ConfigTable::ParseString(s.ToToml(), "study.toml");
  const study::FigureSettings t = study::FigureSettings::FromConfig(again.GetTable("figures"));
  EXPECT_EQ(t.ToToml(), s.ToToml());
  for (const char* bad : {"[figures]\nlevel = [0.5]\n", "[figures]\nlevels = [2.0]\n",
                          "[figures]\nmodels = [\"cam_clay\"]\n", "[figures]\ncases = [\"\"]\n"}) {
    const ConfigTable table = ConfigTable::ParseString(bad, "p.toml");
    try {
      study::FigureSettings::FromConfig(table.GetTable("figures"));
      ADD_FAILURE() << "accepted: " << bad;
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find("p.toml"), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find("figures."), std::string::npos) << error.what();
    }
  }
}

TEST(FigureSettings, CommandLineKeysOverrideTheProgrammes) {
  study::FigureSettings programme, flags;
  programme.levels = {0.5};
  programme.models = std::vector<std::string>{};
  flags.levels = {0.6, 0.7};
  programme.Override(flags);
  EXPECT_EQ(programme.levels, (std::vector<double>{0.6, 0.7}));
  EXPECT_FALSE(programme.Overlays("hypoplastic_clay"));  // still none: the flags left it
}

TEST(FigureSettings, TheProgrammesTableIsReadAndChecked) {
  const std::string base =
      "[study]\nname = \"s\"\n[scale.tiny]\ncount = 100\n[[run]]\nname = \"ncl\"\n"
      "from = \"sample\"\n[[run.stage]]\ntype = \"strain_path\"\npsi_epsilon_deg = 0\n";
  const study::Programme programme = study::Programme::Parse(base + "[figures]\nlevels = [0.55]\n",
                                                             "p.toml", ".", study::Scale::kTiny);
  EXPECT_EQ(programme.figures.levels, (std::vector<double>{0.55}));
  EXPECT_THROW(study::Programme::Parse(base + "[figures]\nlevelz = [0.55]\n", "p.toml", ".",
                                       study::Scale::kTiny),
               InputError);
}

// A joined row (the path convergence's "a+b") belongs to a selection of
// cases when both paths it joins do.
TEST(FigureSelection, AJoinedStateBelongsToTheCasesOfBothItsPaths) {
  Context ctx = Study(TempDir("joined"));
  ctx.states.push_back(
      Row("nc100_psi90+nc1000_psi90", TableKind::kCsl, TableStatus::kDetected, 100));
  StateSelection both;
  both.cases = {"nc100_psi90", "nc1000_psi90"};
  std::vector<std::string> names;
  for (const StateRow* row : ctx.Select(both)) names.push_back(row->case_name);
  EXPECT_EQ(names,
            (std::vector<std::string>{"nc100_psi90", "nc1000_psi90", "nc100_psi90+nc1000_psi90"}));
  StateSelection one;
  one.cases = {"nc100_psi90"};
  names.clear();
  for (const StateRow* row : ctx.Select(one)) names.push_back(row->case_name);
  EXPECT_EQ(names, (std::vector<std::string>{"nc100_psi90"}));
}

}  // namespace
}  // namespace granasym::analysis::figures
