#include "analysis/study_compare.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "analysis/study_compare_files.h"
#include "common/csv_table.h"
#include "common/error.h"
#include "common/text_file.h"

namespace granasym::analysis {
namespace {

namespace fs = std::filesystem;

// A usable state row of one replicate.
StateRow Row(const std::string& case_name, const std::string& stage, TableKind kind, int replicate,
             double psi_sigma, double ln_v, double p, TableStatus status = TableStatus::kDetected) {
  StateRow row;
  row.case_name = case_name;
  row.case_id = "r" + std::to_string(replicate) + "/" + case_name;
  row.stage = stage;
  row.kind = kind;
  row.replicate = replicate;
  row.status = status;
  row.psi_sigma_deg = psi_sigma;
  row.ln_1_plus_e = ln_v;
  row.e = std::expm1(ln_v);
  row.p_kpa = p;
  row.q_over_p = psi_sigma / 25;  // any value that follows ψ_σ
  row.psi_epsilon_deg = kind == TableKind::kCsl ? 90 : kind == TableKind::kNcl ? 0 : 50;
  return row;
}

CompareStudy Study(const std::string& name, int replicates) {
  CompareStudy study;
  study.directory = "/nowhere/" + name;
  study.name = name;
  study.programme = "paper";
  study.scale = replicates > 1 ? "small" : "paper";
  study.replicates = replicates;
  study.count = replicates > 1 ? 3000 : 150000;
  study.study_ncl = "ncl";
  return study;
}

const StateMatch* FindMatch(const StudyComparison& c, const std::string& case_name) {
  for (const StateMatch& m : c.matches) {
    if (m.case_name == case_name) return &m;
  }
  return nullptr;
}

TEST(DifferenceOfMeans, WelchIntervalMatchesAHandComputedValue) {
  // A = {1, 2, 3}: mean 2, s² = 1; B = {4, 6, 8, 10}: mean 7, s² = 20/3.
  // s_a²/n_a = 1/3, s_b²/n_b = 5/3, sum 2; ν = 2² / ((1/3)²/2 + (5/3)²/3)
  // = 216/53 = 4.08, rounded down to 4: t = 2.776, half-width 2.776 √2.
  const MeanDifference d = DifferenceOfMeans({1, 2, 3}, {4, 6, 8, 10});
  EXPECT_DOUBLE_EQ(d.difference, 5.0);
  EXPECT_EQ(d.dof, 4);
  EXPECT_NEAR(d.half_width, 2.776 * std::sqrt(2.0), 1e-12);
  EXPECT_EQ(d.interval, DifferenceInterval::kWelch);
  EXPECT_TRUE(d.excludes_zero());
  // Swapped: the sign flips, the interval stays.
  const MeanDifference swapped = DifferenceOfMeans({4, 6, 8, 10}, {1, 2, 3});
  EXPECT_DOUBLE_EQ(swapped.difference, -5.0);
  EXPECT_DOUBLE_EQ(swapped.half_width, d.half_width);
}

TEST(DifferenceOfMeans, AnIntervalThatHoldsZeroDoesNotDiffer) {
  const MeanDifference d = DifferenceOfMeans({1, 2, 3}, {1.5, 2.5, 3.5});
  EXPECT_DOUBLE_EQ(d.difference, 0.5);
  EXPECT_TRUE(d.has_interval());
  EXPECT_FALSE(d.excludes_zero());
}

TEST(DifferenceOfMeans, ASingleReplicateTakesTheOtherSidesVariance) {
  // B = {11, 12, 13}: s² = 1, n = 3; A's one value 10: d = 2 ± t₂ √(1 (1/3 + 1)).
  const MeanDifference d = DifferenceOfMeans({10}, {11, 12, 13});
  EXPECT_DOUBLE_EQ(d.difference, 2.0);
  EXPECT_EQ(d.dof, 2);
  EXPECT_NEAR(d.half_width, 4.303 * std::sqrt(4.0 / 3.0), 1e-12);
  EXPECT_EQ(d.interval, DifferenceInterval::kVarianceOfB);
  EXPECT_FALSE(d.excludes_zero());  // 2 < 4.97
  EXPECT_EQ(DifferenceOfMeans({11, 12, 13}, {20}).interval, DifferenceInterval::kVarianceOfA);
}

TEST(DifferenceOfMeans, OneReplicateEachHasNoInterval) {
  const MeanDifference d = DifferenceOfMeans({10}, {12});
  EXPECT_DOUBLE_EQ(d.difference, 2.0);
  EXPECT_FALSE(d.has_interval());
  EXPECT_FALSE(d.excludes_zero());
  EXPECT_EQ(d.interval, DifferenceInterval::kNone);
  EXPECT_TRUE(std::isnan(DifferenceOfMeans({}, {1, 2}).difference));
}

// A with three replicates, B with two: one critical state differing by 5°
// in ψ_σ, NCL states equal, one case only in A, one only in B, one gas in
// B, a φ = 0 case that is the other-friction sample in A but B's own.
class CompareStudiesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    a_ = Study("small", 3);
    b_ = Study("changed", 2);
    const double scatter[3] = {-0.5, 0.0, 0.5};
    for (int r = 1; r <= 3; ++r) {
      const double s = scatter[r - 1];
      a_.states.push_back(Row("nc100_psi90", "psi90", TableKind::kCsl, r, 25 + s, 0.57, 30));
      a_.states.push_back(Row("ncl", "p100", TableKind::kNcl, r, 0.1, 0.57 + 0.001 * s, 100));
      a_.states.push_back(Row("oc5_psi90", "psi90", TableKind::kCsl, r, 26 + s, 0.6, 10));
      a_.states.push_back(Row("nc20_psi90", "psi90", TableKind::kCsl, r, 24 + s, 0.6, 8));
      a_.states.push_back(Row("phi0_nc100_psi90", "psi90", TableKind::kCsl, r, 10 + s, 0.5, 30));
      a_.samples[{r, "phi0_nc100_psi90"}] = kSampleOtherFriction;
      a_.ncl_fits[{r, "ncl"}] = {0.68 + 0.01 * s, 0.025 + 0.001 * s};
    }
    a_.ncl_fits[{0, "ncl"}] = {5.0, 1.0};  // the ensemble's fit: never counted
    for (int r = 1; r <= 2; ++r) {
      const double s = r == 1 ? -0.5 : 0.5;
      b_.states.push_back(Row("nc100_psi90", "psi90", TableKind::kCsl, r, 30 + 0.2 * s, 0.57, 30));
      b_.states.push_back(Row("ncl", "p100", TableKind::kNcl, r, 0.1, 0.57 + 0.001 * s, 100));
      b_.states.push_back(Row("nc500_psi90", "psi90", TableKind::kCsl, r, 25 + s, 0.55, 150));
      b_.states.push_back(
          Row("nc20_psi90", "psi90", TableKind::kCsl, r, 0, 0.7, 0.1, TableStatus::kGas));
      b_.states.push_back(Row("phi0_nc100_psi90", "psi90", TableKind::kCsl, r, 11 + s, 0.5, 30));
      b_.ncl_fits[{r, "ncl"}] = {0.70 + 0.01 * s, 0.025 + 0.001 * s};
    }
    // Rows that are no replicate's: an ensemble row and a joined one.
    StateRow ensemble = Row("nc100_psi90", "psi90", TableKind::kCsl, 0, 80, 0.9, 30);
    ensemble.source = study::TableSource::kEnsemble;
    b_.states.push_back(ensemble);
    StateRow joined = Row("nc5_psi50+nc20_psi50", "joined", TableKind::kCompression, 1, 9, 0.5, 9);
    joined.source = study::TableSource::kJoined;
    a_.states.push_back(joined);
  }
  CompareStudy a_, b_;
};

TEST_F(CompareStudiesTest, MatchedStatesCarryBothMeansAndTheirDifference) {
  const StudyComparison c = CompareStudies(a_, b_);
  ASSERT_EQ(c.matches.size(), 2u);           // ncl p100 and nc100_psi90, both of the main sample
  EXPECT_EQ(c.matches[0].case_name, "ncl");  // NCL before critical states
  const StateMatch* m = FindMatch(c, "nc100_psi90");
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(m->sample, kSampleMain);
  EXPECT_EQ(m->kind, TableKind::kCsl);
  EXPECT_EQ(m->a.replicates, 3);
  EXPECT_EQ(m->b.replicates, 2);  // the ensemble row is no replicate
  const size_t psi = static_cast<size_t>(StateQuantity::kPsiSigma);
  EXPECT_DOUBLE_EQ(m->a.mean[psi].mean, 25.0);
  EXPECT_DOUBLE_EQ(m->b.mean[psi].mean, 30.0);
  EXPECT_TRUE(m->a.mean[psi].has_interval());
  const MeanDifference& d = m->difference[psi];
  EXPECT_DOUBLE_EQ(d.difference, 5.0);
  EXPECT_EQ(d.interval, DifferenceInterval::kWelch);
  // s_a²/3 = 0.25/3, s_b²/2 = 0.02/2: ν = 2.44, rounded down to 2, t = 4.303.
  EXPECT_EQ(d.dof, 2);
  EXPECT_NEAR(d.half_width, 4.303 * std::sqrt(0.25 / 3 + 0.01), 1e-12);
  EXPECT_TRUE(d.excludes_zero());
  const size_t lnp = static_cast<size_t>(StateQuantity::kLnP);
  EXPECT_NEAR(m->a.mean[lnp].mean, std::log(30.0), 1e-12);
  EXPECT_DOUBLE_EQ(m->difference[lnp].difference, 0.0);
  EXPECT_FALSE(m->difference[lnp].excludes_zero());
  EXPECT_EQ(c.Differing(StateQuantity::kPsiSigma), 1);
  EXPECT_EQ(c.Differing(StateQuantity::kPsiSigma, TableKind::kNcl), 0);
  EXPECT_EQ(m->a.StatusText(), "detected 3");
}

TEST_F(CompareStudiesTest, UnmatchedStatesAreListedWithTheirStatusOnEachSide) {
  const StudyComparison c = CompareStudies(a_, b_);
  std::map<std::string, const UnmatchedState*> by_case;
  for (const UnmatchedState& u : c.unmatched) by_case[u.sample + "/" + u.case_name] = &u;
  ASSERT_EQ(by_case.size(), c.unmatched.size());
  ASSERT_TRUE(by_case.count("main/oc5_psi90"));
  EXPECT_EQ(by_case["main/oc5_psi90"]->where, "only in A");
  EXPECT_EQ(by_case["main/oc5_psi90"]->status_b, "absent");
  ASSERT_TRUE(by_case.count("main/nc500_psi90"));
  EXPECT_EQ(by_case["main/nc500_psi90"]->where, "only in B");
  EXPECT_EQ(by_case["main/nc500_psi90"]->status_a, "absent");
  EXPECT_EQ(by_case["main/nc500_psi90"]->status_b, "detected 2");
  // All of B's rows are gas: unmatched, with the status that says why.
  ASSERT_TRUE(by_case.count("main/nc20_psi90"));
  EXPECT_EQ(by_case["main/nc20_psi90"]->where, "in both, usable in A only");
  EXPECT_EQ(by_case["main/nc20_psi90"]->status_b, "gas 2");
  // Joined rows are no state of a case and stage.
  for (const UnmatchedState& u : c.unmatched) EXPECT_NE(u.stage, "joined");
}

TEST_F(CompareStudiesTest, StatesOfDifferentSamplesAreNeverMatched) {
  // phi0_nc100_psi90 is the other-friction sample in A and B's own sample
  // in B (B ran it at the study's friction): two unmatched rows, no match.
  const StudyComparison c = CompareStudies(a_, b_);
  EXPECT_EQ(FindMatch(c, "phi0_nc100_psi90"), nullptr);
  int listed = 0;
  for (const UnmatchedState& u : c.unmatched) {
    if (u.case_name != "phi0_nc100_psi90") continue;
    ++listed;
    EXPECT_EQ(u.where, u.sample == kSampleOtherFriction ? "only in A" : "only in B") << u.sample;
  }
  EXPECT_EQ(listed, 2);
  // Both in the other-friction sample: matched.
  for (int r = 1; r <= 2; ++r) b_.samples[{r, "phi0_nc100_psi90"}] = kSampleOtherFriction;
  const StudyComparison again = CompareStudies(a_, b_);
  const StateMatch* m = FindMatch(again, "phi0_nc100_psi90");
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(m->sample, kSampleOtherFriction);
  EXPECT_EQ(again.matches.back().case_name, "phi0_nc100_psi90");  // after the main sample
}

TEST_F(CompareStudiesTest, TheNclFitsAndTheCriticalStateRatioAreCompared) {
  const StudyComparison c = CompareStudies(a_, b_);
  const LineComparison* n = c.Line(kSampleMain, "ncl", "N", "ncl");
  ASSERT_NE(n, nullptr);
  EXPECT_EQ(n->a.n, 3);  // replicate 0 left out
  EXPECT_EQ(n->b.n, 2);
  EXPECT_NEAR(n->a.mean, 0.68, 1e-12);
  EXPECT_NEAR(n->difference.difference, 0.02, 1e-12);
  const LineComparison* lambda = c.Line(kSampleMain, "ncl", "lambda_star", "ncl");
  ASSERT_NE(lambda, nullptr);
  EXPECT_NEAR(lambda->difference.difference, 0.0, 1e-12);
  EXPECT_FALSE(lambda->difference.excludes_zero());
  // M over the detected critical states of each sample: A's 9 of its own
  // (three cases) and 3 of other friction, B's 6 (three cases; its gas
  // rows and the ensemble row left out).
  const LineComparison* m = c.Line(kSampleMain, "csl", "M");
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(m->a.n, 9);
  EXPECT_EQ(m->b.n, 6);
  const LineComparison* other = c.Line(kSampleOtherFriction, "csl", "M");
  ASSERT_NE(other, nullptr);
  EXPECT_EQ(other->a.n, 3);
  EXPECT_EQ(other->b.n, 0);
  EXPECT_FALSE(other->difference.has_interval());
  // Drifting critical states do not count towards M.
  b_.states.push_back(
      Row("nc200_psi90", "psi90", TableKind::kCsl, 1, 40, 0.5, 60, TableStatus::kDrifting));
  EXPECT_EQ(CompareStudies(a_, b_).Line(kSampleMain, "csl", "M")->b.n, 6);
}

TEST_F(CompareStudiesTest, OneReplicateOnASideIsSaidInTheNote) {
  b_.states.erase(std::remove_if(b_.states.begin(), b_.states.end(),
                                 [](const StateRow& r) { return r.replicate == 2; }),
                  b_.states.end());
  const StudyComparison c = CompareStudies(a_, b_);
  const StateMatch* m = FindMatch(c, "nc100_psi90");
  ASSERT_NE(m, nullptr);
  EXPECT_FALSE(m->b.mean[0].has_interval());
  EXPECT_EQ(m->difference[0].interval, DifferenceInterval::kVarianceOfA);
  EXPECT_NE(m->note.find("B has one replicate"), std::string::npos) << m->note;
}

TEST(StateMatch, TheLabelDropsAStageThatEndsTheCaseName) {
  StateMatch m;
  m.case_name = "nc100_psi90";
  m.stage = "psi90";
  EXPECT_EQ(m.Label(), "nc100_psi90");
  m.case_name = "ncl";
  m.stage = "p100";
  EXPECT_EQ(m.Label(), "ncl@p100");
}

TEST(CompareStudies, CasesAreInNumericOrder) {
  CompareStudy a = Study("a", 1), b = Study("b", 1);
  for (const char* name : {"nc1000_psi90", "nc100_psi90", "nc20_psi90", "nc200_psi90"}) {
    a.states.push_back(Row(name, "psi90", TableKind::kCsl, 1, 25, 0.6, 10));
    b.states.push_back(Row(name, "psi90", TableKind::kCsl, 1, 26, 0.6, 10));
  }
  const StudyComparison c = CompareStudies(a, b);
  ASSERT_EQ(c.matches.size(), 4u);
  EXPECT_EQ(c.matches[0].case_name, "nc20_psi90");
  EXPECT_EQ(c.matches[1].case_name, "nc100_psi90");
  EXPECT_EQ(c.matches[2].case_name, "nc200_psi90");
  EXPECT_EQ(c.matches[3].case_name, "nc1000_psi90");
  EXPECT_FALSE(c.matches[0].difference[0].has_interval());  // one replicate each
  EXPECT_NE(c.matches[0].note.find("no interval"), std::string::npos);
}

class CompareFolderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("granasym_compare_" + std::to_string(getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_ / "a");
    fs::create_directories(root_ / "b");
  }
  void TearDown() override { fs::remove_all(root_); }
  std::string P(const std::string& name) const { return (root_ / name).string(); }
  fs::path root_;
};

TEST_F(CompareFolderTest, TheOutputIsNeverAStudyOrInsideOne) {
  EXPECT_NO_THROW(CheckCompareFolder(P("out"), P("a"), P("b")));
  EXPECT_THROW(CheckCompareFolder(P("a"), P("a"), P("b")), InputError);
  EXPECT_THROW(CheckCompareFolder(P("b"), P("a"), P("b")), InputError);
  EXPECT_THROW(CheckCompareFolder(P("a/figures"), P("a"), P("b")), InputError);
  EXPECT_THROW(CheckCompareFolder(P("b/x/y"), P("a"), P("b")), InputError);
  EXPECT_THROW(CheckCompareFolder(P("a/../b/c"), P("a"), P("b")), InputError);
  try {
    CheckCompareFolder(P("a/cmp"), P("a"), P("b"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("inside study A"), std::string::npos) << e.what();
  }
  // A sibling whose name starts with A's is not inside A.
  EXPECT_NO_THROW(CheckCompareFolder(P("ab"), P("a"), P("b")));
}

TEST_F(CompareFolderTest, AAndBMustDiffer) {
  EXPECT_THROW(CheckCompareFolder(P("out"), P("a"), P("a/.")), InputError);
  fs::create_directory_symlink(root_ / "a", root_ / "link");
  EXPECT_THROW(CheckCompareFolder(P("out"), P("a"), P("link")), InputError);
}

TEST_F(CompareFolderTest, ANonEmptyFolderMustBeAnEarlierComparison) {
  fs::create_directories(root_ / "out");
  EXPECT_NO_THROW(CheckCompareFolder(P("out"), P("a"), P("b")));  // empty
  WriteTextFileAtomically(P("out/notes.txt"), "mine\n");
  EXPECT_THROW(CheckCompareFolder(P("out"), P("a"), P("b")), InputError);
  WriteTextFileAtomically(P("out/compare.toml"), "a = \"x\"\n");
  EXPECT_NO_THROW(CheckCompareFolder(P("out"), P("a"), P("b")));
  WriteTextFileAtomically(P("file"), "x\n");
  EXPECT_THROW(CheckCompareFolder(P("file"), P("a"), P("b")), InputError);
}

TEST(DefaultCompareFolder, NamesBothStudies) {
  EXPECT_EQ(DefaultCompareFolder("runs/s35", "/data/study-paper/"), "compare-s35-vs-study-paper");
}

TEST_F(CompareFolderTest, TheFilesHoldOneRowPerMatchAndAHoverLabelPerState) {
  CompareStudy a = Study("small", 3), b = Study("changed", 2);
  for (int r = 1; r <= 3; ++r) {
    a.states.push_back(
        Row("nc100_psi90", "psi90", TableKind::kCsl, r, 25 + 0.5 * (r - 2), 0.57, 30));
    a.states.push_back(Row("ncl", "p100", TableKind::kNcl, r, 0.1, 0.57, 100));
    a.ncl_fits[{r, "ncl"}] = {0.68 + 0.001 * r, 0.025 + 0.0001 * r};
  }
  for (int r = 1; r <= 2; ++r) {
    b.states.push_back(Row("nc100_psi90", "psi90", TableKind::kCsl, r, 30 + 0.5 * r, 0.57, 30));
    b.states.push_back(Row("ncl", "p100", TableKind::kNcl, r, 0.1, 0.58, 100));
    b.states.push_back(Row("nc500_psi90", "psi90", TableKind::kCsl, r, 25, 0.55, 150));
    b.ncl_fits[{r, "ncl"}] = {0.69 + 0.001 * r, 0.026 + 0.0001 * r};
  }
  const StudyComparison c = CompareStudies(a, b);
  const std::string out = P("out");
  WriteComparisonTables(out, c);
  const std::vector<FigureSpec> figures = WriteComparisonFigureData(out, c);
  WriteComparisonSummary(out, c, figures);

  const CsvTextTable states = CsvTextTable::ReadFile(out + "/compare_states.csv");
  ASSERT_EQ(states.rows.size(), 2u);
  const auto& row = states.rows[1];
  EXPECT_EQ(row[states.Column("case_name")], "nc100_psi90");
  EXPECT_EQ(row[states.Column("psi_sigma_deg_differs")], "yes");
  EXPECT_NEAR(std::stod(row[states.Column("diff_psi_sigma_deg")]), 5.75, 1e-9);
  EXPECT_EQ(row[states.Column("difference_interval")], "welch");
  EXPECT_FALSE(states.comments.empty());
  const CsvTextTable unmatched = CsvTextTable::ReadFile(out + "/compare_unmatched.csv");
  ASSERT_EQ(unmatched.rows.size(), 1u);
  EXPECT_EQ(unmatched.rows[0][unmatched.Column("where")], "only in B");
  const CsvTextTable lines = CsvTextTable::ReadFile(out + "/compare_ncl.csv");
  ASSERT_EQ(lines.rows.size(), 3u);  // N, λ*, M
  EXPECT_TRUE(fs::exists(out + "/" + kCompareRecord));

  ASSERT_EQ(figures.size(), 3u);
  EXPECT_EQ(figures[0].stem, "compare_psi_sigma");
  EXPECT_EQ(figures[1].stem, "compare_ln_v");
  EXPECT_EQ(figures[2].stem, "compare_differences");
  for (const FigureSpec& f : figures) EXPECT_TRUE(f.not_drawn.empty()) << f.stem;
  // Two blocks (A, B) of two states, each row ending in its hover label.
  const std::string data = ReadTextFile(out + "/figures/data/compare_states.tsv");
  int labels = 0;
  for (size_t at = data.find("replicate"); at != std::string::npos;
       at = data.find("replicate", at + 1)) {
    ++labels;
  }
  EXPECT_EQ(labels, 4) << data;
  EXPECT_NE(data.find("A small: nc100_psi90 psi90 (csl), 3 replicates; ψ_σ = 25.00 ± "),
            std::string::npos)
      << data;
  EXPECT_TRUE(fs::exists(out + "/figures/data/compare_ncl_a.tsv"));
  const std::string differences = ReadTextFile(out + "/figures/data/compare_differences.tsv");
  EXPECT_NE(differences.find("nc100_psi90 psi90 (csl, main sample): B − A ψ_σ = +5.75 ± "),
            std::string::npos)
      << differences;
  const std::string md = ReadTextFile(out + "/compare.md");
  EXPECT_NE(md.find("2 states matched"), std::string::npos) << md;
  EXPECT_NE(md.find("| nc500_psi90 |"), std::string::npos) << md;
}

}  // namespace
}  // namespace granasym::analysis

namespace granasym::analysis {
namespace {

// The rate study's names against the paper's: renamed, then matched; a rule
// that pools two cases, renames nothing or is malformed is refused.
TEST(RenameCases, TheRateStudysNamesMatchThePapersAfterARename) {
  CompareStudy a = Study("paper", 2), b = Study("rate", 2);
  for (int r = 1; r <= 2; ++r) {
    a.states.push_back(Row("nc100_psi90", "psi90", TableKind::kCsl, r, 25 + r, 0.57, 30));
    b.states.push_back(
        Row("nc100_psi90_I0.001_E500", "psi90", TableKind::kCsl, r, 20 + r, 0.6, 30));
    b.states.push_back(
        Row("nc100_psi90_I0.003_E500", "psi90", TableKind::kCsl, r, 22 + r, 0.6, 30));
  }
  EXPECT_EQ(CompareStudies(a, b).matches.size(), 0u);
  CompareStudy renamed = b;
  RenameCases(&renamed, R"((nc\d+_psi\d+)_I0\.001_E500=$1)", "--rename-b");
  const StudyComparison c = CompareStudies(a, renamed);
  const StateMatch* match = FindMatch(c, "nc100_psi90");
  ASSERT_NE(match, nullptr);
  EXPECT_EQ(match->b.replicates, 2);
  EXPECT_NEAR(match->b.mean[0].mean, 21.5, 1e-12);  // the I* = 1e-3 rows, not the 3e-3 ones
  for (const char* bad :
       {R"((nc\d+_psi\d+)_I0\.00\d_E500=$1)", "nothing_matches=x", "no-equals", "(unclosed=x"}) {
    CompareStudy copy = b;
    EXPECT_THROW(RenameCases(&copy, bad, "--rename-b"), InputError) << bad;
  }
}

}  // namespace
}  // namespace granasym::analysis
