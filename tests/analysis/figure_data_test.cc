#include "analysis/figure_data.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "analysis/quasi_static_selection.h"
#include "analysis/rate_files.h"
#include "common/error.h"
#include "common/text_file.h"
#include "study/state_table.h"
#include "tests/analysis/rate_states_fixture.h"

namespace granasym::analysis {
namespace {

namespace fs = std::filesystem;
constexpr double kDegree = M_PI / 180.0;

StateRow State(TableKind kind, double p, double ln_v, double psi_sigma, double slope) {
  StateRow row;
  row.kind = kind;
  row.status = TableStatus::kDetected;
  row.p_kpa = p;
  row.ln_1_plus_e = ln_v;
  row.e = std::expm1(ln_v);
  row.psi_sigma_deg = psi_sigma;
  row.psi_epsilon_deg = kind == TableKind::kCsl ? 90 : 50;
  row.dln1pe_dlnp = slope;
  return row;
}

TEST(FigureDataOptions, DefaultOptionsAreValid) {
  std::string why;
  EXPECT_TRUE(FigureDataOptions().IsValid(&why)) << why;
  FigureDataOptions bad;
  bad.settings.levels = {0.6, -1.0};
  EXPECT_FALSE(bad.IsValid(&why));
  EXPECT_NE(why.find("levels"), std::string::npos);
}

TEST(ProjectToLevel, ACompressionStateMovesAlongItsOwnAsymptoticLine) {
  const NclLine ncl{0.8, 0.03};
  const StateRow state = State(TableKind::kCompression, 100.0, 0.60, 20.0, -0.05);
  SectionPoint point;
  ASSERT_TRUE(ProjectToLevel(state, 0.59, ncl, 1.0, &point));
  // (0.59 − 0.60)/(−0.05) = 0.2 in ln p, at ψ_σ kept.
  EXPECT_NEAR(point.lnp_shift, 0.2, 1e-12);
  const double p = 100.0 * std::exp(0.2);
  const double pe = std::exp((0.8 - 0.59) / 0.03);
  EXPECT_NEAR(point.p_over_pe, p / pe, 1e-12);
  EXPECT_NEAR(point.q_over_pe, 3.0 / std::sqrt(2.0) * std::tan(20 * kDegree) * p / pe, 1e-12);
  EXPECT_EQ(point.psi_epsilon_deg, 50);
}

TEST(ProjectToLevel, AnIsochoricStateKeepsItsOcrAlongTheNclSlope) {
  const NclLine ncl{0.8, 0.03};
  // The detector's slope of an isochoric path is ~0: the NCL's is used.
  const StateRow state = State(TableKind::kCsl, 50.0, 0.62, 30.0, 1e-12);
  SectionPoint point;
  ASSERT_TRUE(ProjectToLevel(state, 0.61, ncl, 1.0, &point));
  const double ocr = ncl.EquivalentPressure(0.62) / 50.0;
  EXPECT_NEAR(point.p_over_pe, 1.0 / ocr, 1e-12);
  EXPECT_NEAR(point.lnp_shift, 0.01 / 0.03, 1e-12);
}

TEST(ProjectToLevel, AStateFartherThanTheLimitIsSkipped) {
  const NclLine ncl{0.8, 0.03};
  const StateRow state = State(TableKind::kCompression, 100.0, 0.60, 20.0, -0.05);
  SectionPoint point;
  EXPECT_FALSE(ProjectToLevel(state, 0.50, ncl, 1.0, &point));  // 2 in ln p
  EXPECT_TRUE(ProjectToLevel(state, 0.50, ncl, 2.5, &point));
  EXPECT_FALSE(ProjectToLevel(state, 0.60, NclLine{}, 1.0, &point));  // no NCL
}

TEST(PathPsiEpsilon, StrainIncrementsGiveTheDirection) {
  // ψ_ε = 90°: ε_a = t √(2/3), ε_r = −t/√6 (SPEC §2 inverse); ψ_ε = 0°: ε_a = ε_r.
  std::vector<double> a90, r90, a0, r0;
  for (int k = 0; k < 10; ++k) {
    a90.push_back(k * std::sqrt(2.0 / 3.0));
    r90.push_back(-k / std::sqrt(6.0));
    a0.push_back(0.01 * k);
    r0.push_back(0.01 * k);
  }
  for (double psi : PathPsiEpsilon(a90, r90, 2)) EXPECT_NEAR(psi, 90.0, 1e-9);
  for (double psi : PathPsiEpsilon(a0, r0, 1)) EXPECT_NEAR(psi, 0.0, 1e-9);
}

TEST(PickStretchingDirections, TheFirstCrossingOfEachTargetIsInterpolated) {
  // ψ_ε rises 0 → 100° over rows 0..10, then falls back to 90°.
  std::vector<double> psi, p, ln_v, psi_sigma;
  for (int k = 0; k <= 10; ++k) psi.push_back(10.0 * k);
  psi.push_back(95.0);
  psi.push_back(90.0);
  for (size_t k = 0; k < psi.size(); ++k) {
    p.push_back(100.0 * std::exp(0.1 * k));
    ln_v.push_back(0.6 - 0.001 * k);
    psi_sigma.push_back(2.0 * k);
  }
  const std::vector<StretchingPick> picks =
      PickStretchingDirections(psi, p, ln_v, psi_sigma, {45.0, 95.0, 120.0});
  ASSERT_EQ(picks.size(), 2u);  // 120° is never reached
  EXPECT_EQ(picks[0].psi_epsilon_deg, 45.0);
  EXPECT_NEAR(picks[0].row, 4.5, 1e-12);
  EXPECT_NEAR(picks[0].p_kpa, 100.0 * std::exp(0.45), 1e-9);  // log-linear in p
  EXPECT_NEAR(picks[0].ln_1_plus_e, 0.6 - 0.0045, 1e-12);
  EXPECT_NEAR(picks[0].psi_sigma_deg, 9.0, 1e-12);
  // 95° is crossed rising (row 9.5) before it is reached falling (row 11).
  EXPECT_NEAR(picks[1].row, 9.5, 1e-12);
}

TEST(SectionLevels, LevelsSpanTheMiddleOfTheRange) {
  const std::vector<double> levels = SectionLevels({0.50, 0.55, 0.62, 0.70}, 3);
  ASSERT_EQ(levels.size(), 3u);
  EXPECT_NEAR(levels[0], 0.54, 1e-12);
  EXPECT_NEAR(levels[1], 0.60, 1e-12);
  EXPECT_NEAR(levels[2], 0.66, 1e-12);
  EXPECT_EQ(SectionLevels({0.600, 0.604}, 3).size(), 1u);
  EXPECT_TRUE(SectionLevels({}, 3).empty());
}

class ModelOverlayTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per test and process: ctest -j runs the tests of this
    // fixture in parallel processes.
    folder_ = (fs::temp_directory_path() /
               ("granasym_overlay_" +
                std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
                std::to_string(::getpid())))
                  .string();
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }
  void WriteModel(double n, double lambda) {
    WriteTextFileAtomically(folder_ + "/model_curve.csv",
                            "psi_sigma_deg,psi_epsilon_deg,ocr,ln_ocr,p_over_pe,q_over_pe\n"
                            "0,0,1,0,1,0\n30,90,2,0.693,0.5,0.6\n");
    std::string lines = "# model asymptotic lines\n# columns: ...\n";
    for (double psi : {0.0, 90.0}) {
      for (int k = 0; k <= 4; ++k) {
        const double ln_p = k;
        const double ln_ocr = psi == 0 ? 0 : std::log(2.0);
        lines += std::to_string(psi) + "," + std::to_string(ln_p) + "," +
                 std::to_string(n - lambda * (ln_p + ln_ocr)) + "," + (psi == 0 ? "0" : "30") +
                 "\n";
      }
      lines += "\n\n";
    }
    WriteTextFileAtomically(folder_ + "/model_lines.dat", lines);
  }
  std::string folder_;
};

TEST_F(ModelOverlayTest, TheModelsNclComesFromItsIsotropicLine) {
  WriteModel(0.9, 0.05);
  const ModelOverlay model = ReadModelOverlay(folder_, "hypoplastic_clay");
  EXPECT_NEAR(model.ncl.n, 0.9, 1e-6);
  EXPECT_NEAR(model.ncl.lambda, 0.05, 1e-6);
  ASSERT_EQ(model.lines.size(), 2u);
  EXPECT_EQ(model.lines[1].psi_sigma_deg, 30);
  EXPECT_EQ(model.lines[1].ln_p.size(), 5u);
}

TEST_F(ModelOverlayTest, TheSectionIsRescaledToTheStudysEquivalentPressure) {
  WriteModel(0.9, 0.05);
  const ModelOverlay model = ReadModelOverlay(folder_, "modified_cam_clay");
  std::vector<double> x, y;
  ModelSectionAt(model, 0.7, NclLine{0.9, 0.05}, &x, &y);  // the same NCL: unchanged
  ASSERT_EQ(x.size(), 2u);
  EXPECT_NEAR(x[1], 0.5, 1e-6);
  EXPECT_NEAR(y[1], 0.6, 1e-6);
  // The study's NCL lower by 0.05 at λ* = 0.05: its p_e* is e^-1 of the model's.
  ModelSectionAt(model, 0.7, NclLine{0.85, 0.05}, &x, &y);
  EXPECT_NEAR(x[1], 0.5 * std::exp(1.0), 1e-5);
  EXPECT_NEAR(y[1], 0.6 * std::exp(1.0), 1e-5);
}

TEST_F(ModelOverlayTest, AMalformedLineNamesTheFileAndLine) {
  WriteModel(0.9, 0.05);
  WriteTextFileAtomically(folder_ + "/model_lines.dat", "# header\n0,1,abc,0\n");
  try {
    ReadModelOverlay(folder_, "hypoplastic_clay");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("model_lines.dat:2"), std::string::npos) << e.what();
  }
}

TEST(WriteFigureData, AFolderWithoutAStateTableIsAnInputError) {
  const std::string folder = (fs::temp_directory_path() / "granasym_no_study").string();
  fs::create_directories(folder);
  EXPECT_THROW(WriteFigureData(folder), InputError);
  fs::remove_all(folder);
}

TEST(WriteFigureIndex, OneRowPerFigureWithTabsRemovedFromFields) {
  const std::string folder = (fs::temp_directory_path() / "granasym_figure_index").string();
  fs::create_directories(folder);
  FigureSpec a{"fig09_ncl", "9", "NCL", "a\tcaption\nover lines", "ncl.gp", {}, ""};
  FigureSpec b{"fig17_asbs_sections", "17", "ASBS",  "Not drawn: no NCL.",
               "asbs_sections.gp",    {},   "no NCL"};
  WriteFigureIndex(folder, {a, b});
  EXPECT_EQ(ReadTextFile(folder + "/figures/index.tsv"),
            "stem\tfigure\ttitle\tcaption\n"
            "fig09_ncl\t9\tNCL\ta caption over lines\n"
            "fig17_asbs_sections\t17\tASBS\tNot drawn: no NCL.\n");
  fs::remove_all(folder);
}

// A study folder with a state table but no case, and the stems WriteFigureData lists.
std::vector<std::string> Stems(const std::vector<FigureSpec>& figures) {
  std::vector<std::string> stems;
  for (const FigureSpec& f : figures) stems.push_back(f.stem);
  return stems;
}

fs::path BareStudy(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "granasym_tests" / "figure_data" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  WriteTextFileAtomically((dir / "study.toml").string(),
                          "programme = \"rate\"\nscale = \"tiny\"\nncl = \"ncl\"\n");
  study::WriteStateTable(dir.string());
  return dir;
}

TEST(WriteFigureData, OnlyThePaperFiguresThatTheCasesDeclareAreListed) {
  const fs::path dir = BareStudy("declared");
  EXPECT_TRUE(WriteFigureData(dir.string()).empty());
  // A case (not run) that serves Figs. 9 and 22: those two, not drawn.
  fs::create_directories(dir / "cases/r1/ncl");
  WriteTextFileAtomically((dir / "cases/r1/ncl/case.toml").string(),
                          "id = \"r1/ncl\"\nname = \"ncl\"\nreplicate = 1\nkey = \"k\"\n"
                          "figures = \"9, 22\"\n");
  const std::vector<FigureSpec> figures = WriteFigureData(dir.string());
  EXPECT_EQ(Stems(figures), (std::vector<std::string>{"fig09_ncl", "fig22_inertial_number"}));
  for (const FigureSpec& f : figures) EXPECT_FALSE(f.not_drawn.empty()) << f.stem;
}

TEST(WriteFigureData, TheRateFiguresComeWithTheRateStudy) {
  const fs::path dir = BareStudy("rate");
  const RateStudy rate = RateStudy::Analyse(rate_fixture::CriticalStates());
  WriteRateFiles(dir.string(), rate);
  const std::vector<FigureSpec> figures = WriteFigureData(dir.string());
  ASSERT_EQ(Stems(figures),
            (std::vector<std::string>{"rate_psi_sigma_p", "rate_csl_ncl",
                                      "rate_critical_state_ratio", "rate_against_models"}));
  auto variable = [](const FigureSpec& f, const std::string& name) {
    for (const auto& [key, value] : f.variables) {
      if (key == name) return value;
    }
    return std::string("absent");
  };
  for (const FigureSpec& f : figures) EXPECT_TRUE(f.not_drawn.empty()) << f.stem << f.not_drawn;
  // (a): one panel (ψ_ε = 90°), one curve per rate (4 I* and 167 1/s).
  EXPECT_EQ(variable(figures[0], "n_panels"), "1");
  EXPECT_EQ(variable(figures[0], "panel_blocks"), "'5'");
  EXPECT_EQ(variable(figures[0], "rate_titles"),
            "'\"I* = 0.0003\" \"I* = 0.001\" \"I* = 0.003\" \"I* = 0.01\" \"‖D‖ = 167 1/s\"'");
  EXPECT_TRUE(fs::exists(dir / "figures/data/rate_psi_sigma_1.tsv"));
  // (b): a CSL per rate with two starts; (c): a quasi-static line per start.
  EXPECT_EQ(variable(figures[1], "n_lines"), "5");
  EXPECT_EQ(variable(figures[2], "n_fits"), "2");
  EXPECT_EQ(variable(figures[2], "band_low"), "0.81");
  EXPECT_EQ(variable(figures[2], "band_high"), "0.95");
  EXPECT_NE(figures[2].caption.find("Latham, Abe & Mora (2005"), std::string::npos)
      << figures[2].caption;
  EXPECT_NE(figures[2].caption.find("Mair, Frye & Marone (2002"), std::string::npos)
      << figures[2].caption;
  const std::string limits =
      ReadTextFile((dir / "figures/data/rate_critical_state_limits.tsv").string());
  EXPECT_NE(limits.find("NC 100 kPa: M_0 = "), std::string::npos) << limits;
  // The x axis reaches left of the limits, a third of the smallest measured I.
  EXPECT_LT(std::stod(variable(figures[2], "x_min")), 1e-4);
  // Without the rate files, no rate figure.
  fs::remove(dir / kRateStatesFile);
  EXPECT_TRUE(WriteFigureData(dir.string()).empty());
}

int Count(const std::string& text, const std::string& part) {
  int n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

TEST(WriteFigureData, TheDrainedCriticalStatesJoinTheMFigure) {
  const fs::path dir = BareStudy("rate_drained");
  RateStudy rate = RateStudy::Analyse(rate_fixture::CriticalStates());
  rate.drained = DrainedStudy::Analyse(rate_fixture::DrainedStates(4.0), rate.options);
  WriteRateFiles(dir.string(), rate);
  const std::vector<FigureSpec> figures = WriteFigureData(dir.string());
  const FigureSpec* m = nullptr;
  for (const FigureSpec& f : figures) {
    if (f.stem == "rate_critical_state_ratio") m = &f;
  }
  ASSERT_NE(m, nullptr);
  EXPECT_TRUE(m->not_drawn.empty()) << m->not_drawn;
  auto variable = [m](const std::string& name) {
    for (const auto& [key, value] : m->variables) {
      if (key == name) return value;
    }
    return std::string("absent");
  };
  // Two 90° fits (20 and 100 kPa) and one drained fit per σ_r (5, 20, 100, 500 kPa).
  EXPECT_EQ(variable("n_fits"), "6");
  EXPECT_EQ(variable("n_starts"), "4");
  const std::string limits =
      ReadTextFile((dir / "figures/data/rate_critical_state_limits.tsv").string());
  EXPECT_NE(limits.find("drained at sigma_r = 5 kPa: M_0 = 0.920"), std::string::npos) << limits;
  const std::string groups =
      ReadTextFile((dir / "figures/data/rate_critical_state_groups.tsv").string());
  EXPECT_EQ(Count(groups, "drained at sigma_r"), 4) << groups;
  // (a) gets a panel of the drained ψ_σ against p: one curve per rank of the
  // axial rate (three), each through the four σ_r, coloured as the nearest I*.
  const FigureSpec& a = figures.front();
  ASSERT_EQ(a.stem, "rate_psi_sigma_p");
  std::map<std::string, std::string> v(a.variables.begin(), a.variables.end());
  EXPECT_EQ(v["n_panels"], "2");
  EXPECT_EQ(v["panel_blocks"], "'5 3'");
  EXPECT_NE(v["panel_titles"].find("\"drained, σ_r = p_0\""), std::string::npos)
      << v["panel_titles"];
  const std::string panel = ReadTextFile((dir / "figures/data/rate_psi_sigma_2.tsv").string());
  EXPECT_NE(panel.find("drained, I ≈ 0.0003, E = 500 MPa"), std::string::npos) << panel;
  EXPECT_EQ(Count(panel, "\t9\t"), 12) << panel;
  // Drained cases alone still make the rate figures.
  fs::remove(dir / kRateStatesFile);
  EXPECT_FALSE(WriteFigureData(dir.string()).empty());
}

// A study whose drained cases differ by material and not by rate (what sets
// M, issue 39 §2: studies/programmes/critical_state_friction.toml): each
// material is a series of its own, with its own colour and a legend label
// of what differs (here the damping χ and the stiffness ratio), drawn side
// by side in I and p; what the materials share is the figure's note. No
// label says "?" or "nan" (the study has no rate group to take E from).
TEST(WriteFigureData, DrainedMaterialsAreSeriesOfTheirOwn) {
  const fs::path dir = BareStudy("rate_materials");
  std::vector<DrainedState> states;
  for (const DrainedState& s : rate_fixture::DrainedStates(0.0)) {
    if (s.radial_stress_kpa != 100 || s.inertial_number_dmax != 1e-3) continue;
    for (const auto& [damping, ratio] :
         {std::pair{0.5, 0.3}, std::pair{0.05, 0.3}, std::pair{0.5, 1.0}}) {
      DrainedState m = s;
      m.case_name = fmt::format("nc100_drained_chi{:g}_kr{:g}", damping, ratio);
      m.local_damping = damping;
      m.stiffness_ratio = ratio;
      m.q_over_p += damping / 10;  // the materials' M differ
      states.push_back(m);
    }
  }
  RateStudy rate = RateStudy::Analyse({});
  rate.drained = DrainedStudy::Analyse(states, rate.options);
  ASSERT_EQ(rate.drained.groups.size(), 3u);
  EXPECT_EQ(rate.ReferenceModulus(), 500);  // from the drained groups
  WriteRateFiles(dir.string(), rate);
  const std::vector<FigureSpec> figures = WriteFigureData(dir.string());
  const FigureSpec* a = nullptr;
  const FigureSpec* c = nullptr;
  for (const FigureSpec& f : figures) {
    if (f.stem == "rate_psi_sigma_p") a = &f;
    if (f.stem == "rate_critical_state_ratio") c = &f;
    for (const auto& [key, value] : f.variables) {
      EXPECT_EQ(value.find('?'), std::string::npos) << f.stem << " " << key << " = " << value;
      EXPECT_EQ(value.find("nan"), std::string::npos) << f.stem << " " << key << " = " << value;
    }
    EXPECT_EQ(f.caption.find("nan"), std::string::npos) << f.stem << ": " << f.caption;
    EXPECT_EQ(f.not_drawn.find("nan"), std::string::npos) << f.stem << ": " << f.not_drawn;
  }
  ASSERT_NE(a, nullptr);
  ASSERT_NE(c, nullptr);
  EXPECT_TRUE(c->not_drawn.empty()) << c->not_drawn;
  std::map<std::string, std::string> v(c->variables.begin(), c->variables.end());
  // No start of an isochoric path: the three materials are the series, in
  // the colours 1-3, labelled by χ and k_t/k_n (E and f are shared).
  EXPECT_EQ(v["n_starts"], "0");
  EXPECT_EQ(v["n_materials"], "3");
  EXPECT_EQ(v["material_titles"],
            "'\"χ = 0.05, k_t/k_n = 0.3\" \"χ = 0.5, k_t/k_n = 0.3\" \"χ = 0.5, k_t/k_n = 1\"'");
  EXPECT_EQ(v["material_colours"], "'1 2 3'");
  EXPECT_EQ(v["modulus_note"], "'E = 500 MPa, f = 0.3, σ_r = 100 kPa'");
  EXPECT_EQ(v["n_isochoric"], "0");
  EXPECT_EQ(v["n_drained"], "3");
  EXPECT_NE(c->caption.find("labelled by what differs"), std::string::npos) << c->caption;
  // The groups: one block per material, its own colour, the measured I kept
  // and the drawn I 4 % apart.
  const std::string groups =
      ReadTextFile((dir / "figures/data/rate_critical_state_groups.tsv").string());
  EXPECT_EQ(Count(groups, "drained at sigma_r = 100 kPa"), 3) << groups;
  std::set<std::string> drawn, colours;
  std::istringstream lines(groups);
  for (std::string line; std::getline(lines, line);) {
    std::vector<std::string> fields;
    std::istringstream in(line);
    for (std::string f; std::getline(in, f, '\t');) fields.push_back(f);
    if (fields.size() != 7 || fields[0] == "inertial_number") continue;
    EXPECT_NEAR(std::stod(fields[0]), 1e-3, 1e-12) << line;
    colours.insert(fields[5]);
    drawn.insert(fields[6]);
  }
  EXPECT_EQ(colours, (std::set<std::string>{"1", "2", "3"})) << groups;
  EXPECT_EQ(drawn.size(), 3u) << groups;
  // (a): the drained panel's curves, one colour per material, with the legend.
  std::map<std::string, std::string> va(a->variables.begin(), a->variables.end());
  EXPECT_EQ(va["n_materials"], "3");
  EXPECT_EQ(va["material_titles"], v["material_titles"]);
  const std::string panel = ReadTextFile((dir / "figures/data/rate_psi_sigma_1.tsv").string());
  EXPECT_NE(panel.find("drained, I ≈ 0.001, χ = 0.05, k_t/k_n = 0.3"), std::string::npos) << panel;
}

TEST(WriteFigureData, TheQuasiStaticSetStandsBesideThePaperRate) {
  const fs::path dir = BareStudy("rate_models");
  RateStudy rate = RateStudy::Analyse(rate_fixture::CriticalStates());
  rate.drained = DrainedStudy::Analyse(rate_fixture::DrainedStates(0.0), rate.options);
  WriteRateFiles(dir.string(), rate);
  auto find = [](const std::vector<FigureSpec>& figures) {
    for (const FigureSpec& f : figures) {
      if (f.stem == "rate_against_models") return f;
    }
    ADD_FAILURE() << "no rate_against_models";
    return FigureSpec{};
  };
  // Uncalibrated: the default selection, the smallest I* with a CSL from two starts.
  FigureSpec f = find(WriteFigureData(dir.string()));
  EXPECT_TRUE(f.not_drawn.empty()) << f.not_drawn;
  std::map<std::string, std::string> v(f.variables.begin(), f.variables.end());
  EXPECT_EQ(v["quasi_title"], "'I* = 0.0003'");
  EXPECT_EQ(v["n_quasi_static"], "1");
  EXPECT_EQ(v["n_paper_rate"], "1");
  EXPECT_EQ(v["n_models"], "0");
  EXPECT_NE(f.caption.find("not yet calibrated"), std::string::npos) << f.caption;
  // The selection that `study calibrate` wrote decides: I* = 0.003, both starts.
  WriteQuasiStaticSelection(dir.string(), SelectQuasiStatic(rate, 3e-3));
  f = find(WriteFigureData(dir.string()));
  EXPECT_NE(f.caption.find("I* = 0.003 (filled circles: the quasi-static set, "
                           "calibration/quasi_static.toml)"),
            std::string::npos)
      << f.caption;
  const std::string quasi =
      ReadTextFile((dir / "figures/data/rate_models_quasi_static.tsv").string());
  // Two groups (the starts) at ψ_ε = 90°, drawn 0.6° to the left; ψ_σ = 25 + 400·3e-3.
  EXPECT_EQ(Count(quasi, "\n89.4\t26.2"), 2) << quasi;
  const std::string paper =
      ReadTextFile((dir / "figures/data/rate_models_paper_rate.tsv").string());
  EXPECT_EQ(Count(paper, "\n90.6\t35\t"), 2) << paper;
  // (b): the drained states of the quasi-static set, the slowest axial rate
  // of each of the four σ_r, three replicates, as filled triangles (9).
  const std::string states = ReadTextFile((dir / "figures/data/rate_models_states.tsv").string());
  const size_t block = states.find("drained triaxial, slowest axial rate");
  ASSERT_NE(block, std::string::npos) << states;
  EXPECT_EQ(Count(states.substr(block), "\t9\n"), 12) << states.substr(block);
  v = std::map<std::string, std::string>(f.variables.begin(), f.variables.end());
  EXPECT_NE(v["psi_titles"].find("\"drained\""), std::string::npos) << v["psi_titles"];
}

TEST(WriteFigureData, TheExtensionSweepHasItsFigureWhenItHasAnExtensionStep) {
  const fs::path dir = BareStudy("rate_extension");
  std::vector<RateState> states = rate_fixture::CriticalStates();
  for (const RateState& s : rate_fixture::ExtensionSweep()) states.push_back(s);
  WriteRateFiles(dir.string(), RateStudy::Analyse(states));
  const std::vector<FigureSpec> figures = WriteFigureData(dir.string());
  ASSERT_EQ(Stems(figures), (std::vector<std::string>{"rate_psi_sigma_p", "rate_csl_ncl",
                                                      "rate_critical_state_ratio", "rate_extension",
                                                      "rate_against_models"}));
  const FigureSpec& f = figures[3];
  EXPECT_TRUE(f.not_drawn.empty()) << f.not_drawn;
  std::map<std::string, std::string> v(f.variables.begin(), f.variables.end());
  EXPECT_EQ(v["n_sweeps"], "2");
  EXPECT_EQ(v["n_steps"], "2");      // both sweeps have usable steps
  EXPECT_EQ(v["n_liquefied"], "1");  // NC 20 kPa from 110°
  EXPECT_EQ(v["n_limits"], "1");     // NC 100 kPa: ψ_ε(d) = 120°
  const std::string limits =
      ReadTextFile((dir / "figures/data/rate_extension_limits.tsv").string());
  EXPECT_NE(limits.find("psi_epsilon(d) = 120.0 +- "), std::string::npos) << limits;
  const std::string liquefied =
      ReadTextFile((dir / "figures/data/rate_extension_liquefied.tsv").string());
  EXPECT_NE(liquefied.find("\n110\t0\t1\n120\t0\t1"), std::string::npos) << liquefied;
  // A rate study without ψ_ε > 90° has no sweep figure (the test above).
}

// Fig. 5 reads the model runs' result.csv by the names of
// common/quantity_names.h and, in runs of older versions, by their former
// names (void_ratio for e): both are drawn alike.
TEST(WriteFigureData, ModelRunsWithTheFormerColumnNamesAreDrawnToo) {
  const fs::path dir = BareStudy("model_paths");
  const std::string rows =
      "0,100,100,100,0,0.8,0,0,0,0,45,1\n1,150,120,130,30,0.75,0.01,0.002,0.02,10,45,1.1\n";
  const std::vector<std::pair<std::string, std::string>> runs = {
      {"current",
       "time_s,sigma_a_kpa,sigma_r_kpa,p_kpa,q_kpa,e,eps_a,eps_r,strain_path,psi_sigma_deg,"
       "psi_epsilon_deg,ocr\n"},
      {"former",
       "time_s,stress_a_kpa,stress_r_kpa,p_kpa,q_kpa,void_ratio,strain_a,strain_r,strain_path,"
       "psi_sigma_deg,psi_epsilon_deg,ocr\n"}};
  for (const auto& [name, header] : runs) {
    fs::create_directories(dir / "models" / name);
    WriteTextFileAtomically((dir / "models" / name / "result.csv").string(), header + rows);
    WriteTextFileAtomically((dir / "models" / name / "done.toml").string(), "key = \"k\"\n");
  }
  const std::vector<FigureSpec> figures = WriteFigureData(dir.string());
  ASSERT_EQ(Stems(figures), (std::vector<std::string>{"fig05_model_paths"}));
  EXPECT_TRUE(figures[0].not_drawn.empty()) << figures[0].not_drawn;
  const std::map<std::string, std::string> v(figures[0].variables.begin(),
                                             figures[0].variables.end());
  EXPECT_EQ(v.at("n_paths"), "2");
  // Each block: p, ln(1 + e), ψ_σ of the last row.
  const std::string data = ReadTextFile((dir / "figures/data/fig05_paths.tsv").string());
  char last_row[64];
  std::snprintf(last_row, sizeof(last_row), "130\t%.8g\t10\n", std::log1p(0.75));
  const size_t first = data.find(last_row);
  ASSERT_NE(first, std::string::npos) << data;
  EXPECT_NE(data.find(last_row, first + 1), std::string::npos) << data;
}

}  // namespace
}  // namespace granasym::analysis
