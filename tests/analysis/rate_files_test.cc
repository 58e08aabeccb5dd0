#include "analysis/rate_files.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "common/csv_table.h"
#include "common/error.h"
#include "tests/analysis/rate_states_fixture.h"

namespace granasym::analysis {
namespace {
namespace fs = std::filesystem;
using rate_fixture::CriticalStates;
using rate_fixture::DrainedStates;
using rate_fixture::kLambda;
using rate_fixture::kM0;

fs::path Folder(const char* name) {
  const fs::path dir = fs::temp_directory_path() / "granasym_tests" / "rate_files" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(ReadRateStates, EveryColumnOfTheTableReadsBackIntoItsMember) {
  const fs::path dir = Folder("every_column");
  RateState s;
  s.replicate = 3;
  s.case_name = "nc20, psi0";  // a comma: quoted in the file
  s.stage = "p1000";
  s.flags = "rate_affected;overlap_above_2pct";
  s.kind = TableKind::kNcl;
  s.status = TableStatus::kDrifting;
  s.youngs_modulus_mpa = 500;
  s.psi_epsilon_deg = 0;
  s.start_p_kpa = 20;
  s.rule = dem::RateRule::kInertial;
  s.inertial_number = 1e-3;
  s.stretching_rate = 167;
  s.p_kpa = 998.5;
  s.e = 0.61;
  s.ln_1_plus_e = std::log1p(0.61);
  s.psi_sigma_deg = 0.25;
  s.q_over_p = 0.01;
  s.ocr = 1.02;
  s.inertial_number_dmin = 2e-4;
  s.inertial_number_dmax = 9e-4;
  s.stiffness_number = 4100;
  s.path_n = 0.71;
  s.path_lambda = 0.028;
  s.path_p_min_kpa = 60;
  s.path_p_max_kpa = 4000;
  RateStudy study = RateStudy::Analyse({s});
  WriteRateFiles(dir.string(), study);
  const std::vector<RateState> back = ReadRateStates(dir.string());
  ASSERT_EQ(back.size(), 1u);
  const RateState& b = back[0];
  EXPECT_EQ(b.replicate, s.replicate);
  EXPECT_EQ(b.case_name, s.case_name);
  EXPECT_EQ(b.stage, s.stage);
  EXPECT_EQ(b.flags, s.flags);
  EXPECT_EQ(b.kind, s.kind);
  EXPECT_EQ(b.status, s.status);
  EXPECT_EQ(b.rule, s.rule);
  for (double RateState::*member :
       {&RateState::youngs_modulus_mpa, &RateState::psi_epsilon_deg, &RateState::start_p_kpa,
        &RateState::inertial_number, &RateState::stretching_rate, &RateState::p_kpa, &RateState::e,
        &RateState::ln_1_plus_e, &RateState::psi_sigma_deg, &RateState::q_over_p, &RateState::ocr,
        &RateState::inertial_number_dmin, &RateState::inertial_number_dmax,
        &RateState::stiffness_number, &RateState::path_n, &RateState::path_lambda,
        &RateState::path_p_min_kpa, &RateState::path_p_max_kpa}) {
    EXPECT_NEAR(b.*member, s.*member, 1e-9 * std::abs(s.*member));
  }
}

TEST(WriteRateFiles, ATableWithoutRowsHasTheHeaderOfItsColumns) {
  const fs::path dir = Folder("empty");
  WriteRateFiles(dir.string(), RateStudy::Analyse(CriticalStates()));  // no drained cases
  const CsvTextTable limits = CsvTextTable::ReadFile((dir / kRateDrainedLimitFile).string());
  EXPECT_TRUE(limits.rows.empty());
  // An estimate is two columns, a comparison three.
  for (const char* column : {"m_mean", "m_ci95", "m_difference", "m_difference_ci95", "m_agreement",
                             "ln_1_plus_e_agreement", "verdict", "reason"}) {
    EXPECT_GE(limits.Find(column), 0) << column;
  }
  EXPECT_TRUE(ReadDrainedStates(dir.string()).empty());
  RemoveRateFiles(dir.string());
  EXPECT_FALSE(fs::exists(dir / kRateStatesFile));
  EXPECT_FALSE(fs::exists(dir / kRateDrainedCriticalFile));
  EXPECT_FALSE(ReadRateStudy(dir.string()).has_value());
}

TEST(WriteRateFiles, TheStatesReadBackAndEveryTableHasItsRows) {
  const fs::path dir = Folder("write");
  const RateStudy study = RateStudy::Analyse(CriticalStates());
  WriteRateFiles(dir.string(), study);
  const std::vector<RateState> back = ReadRateStates(dir.string());
  ASSERT_EQ(back.size(), study.states.size());
  for (size_t k = 0; k < back.size(); ++k) {
    EXPECT_EQ(back[k].rule, study.states[k].rule);
    EXPECT_EQ(back[k].start_p_kpa, study.states[k].start_p_kpa);
    EXPECT_NEAR(back[k].psi_sigma_deg, study.states[k].psi_sigma_deg, 1e-8);
    EXPECT_NEAR(back[k].ln_1_plus_e, study.states[k].ln_1_plus_e, 1e-9);
  }
  // The analysis of what was read back is the same.
  const RateStudy again = RateStudy::Analyse(back);
  ASSERT_EQ(again.verdicts.size(), study.verdicts.size());
  EXPECT_EQ(again.verdicts[0].verdict, study.verdicts[0].verdict);
  auto rows = [&dir](const char* name) {
    const CsvTextTable table = CsvTextTable::ReadFile((dir / name).string());
    return table.rows.size();
  };
  EXPECT_EQ(rows(kRateSummaryFile), study.groups.size());
  EXPECT_EQ(rows(kRateLinesFile), study.lines.size());
  EXPECT_EQ(rows(kRateQuasiStaticFile), study.quasi_static.size());
  EXPECT_EQ(rows(kRateIndependenceFile), 2u);
  const CsvTextTable verdicts = CsvTextTable::ReadFile((dir / kRateIndependenceFile).string());
  EXPECT_EQ(verdicts.rows[0][verdicts.Column("verdict")], "rate_dependent");
  EXPECT_EQ(verdicts.rows[0][verdicts.Column("psi_sigma_deg_agreement")], "differ");
}

TEST(ExtensionSweep, BothFilesHaveTheirRows) {
  const fs::path dir = Folder("extension");
  const RateStudy study = RateStudy::Analyse(rate_fixture::ExtensionSweep());
  WriteRateFiles(dir.string(), study);
  const CsvTextTable steps = CsvTextTable::ReadFile((dir / kRateExtensionFile).string());
  EXPECT_EQ(steps.rows.size(), 9u);
  EXPECT_EQ(steps.rows[2][steps.Column("status")], "liquefied");
  const CsvTextTable limits = CsvTextTable::ReadFile((dir / kRateExtensionLimitFile).string());
  ASSERT_EQ(limits.rows.size(), 2u);
  EXPECT_EQ(limits.rows[1][limits.Column("result")], "limit_d");
  EXPECT_NEAR(std::stod(limits.rows[1][limits.Column("psi_d_deg_mean")]), 120.0, 1e-6);
  EXPECT_NE(limits.rows[0][limits.Column("text")].find("liquefied at psi_epsilon = 110"),
            std::string::npos);
}

TEST(DrainedStudy, TheFilesReadBackAndMalformedNumbersNameTheLine) {
  const fs::path dir = Folder("drained");
  EXPECT_TRUE(ReadDrainedStates(dir.string()).empty());
  RateStudy study = RateStudy::Analyse(CriticalStates());
  study.drained = DrainedStudy::Analyse(DrainedStates(4.0), study.options);
  WriteRateFiles(dir.string(), study);
  const std::vector<DrainedState> back = ReadDrainedStates(dir.string());
  ASSERT_EQ(back.size(), study.drained.states.size());
  const DrainedStudy again = DrainedStudy::Analyse(back, study.options);
  EXPECT_NEAR(again.critical.at(0).m.mean, kM0, 1e-8);
  EXPECT_NEAR(again.critical.at(0).lambda.mean, kLambda, 1e-7);
  auto table = [&dir](const char* name) { return CsvTextTable::ReadFile((dir / name).string()); };
  EXPECT_EQ(table(kRateDrainedFile).rows.size(), 12u);
  EXPECT_EQ(table(kRateDrainedLimitFile).rows.size(), 4u);
  const CsvTextTable critical = table(kRateDrainedCriticalFile);
  ASSERT_EQ(critical.rows.size(), 1u);
  EXPECT_NEAR(std::stod(critical.rows[0][critical.Column("m_mean")]), kM0, 1e-8);
  EXPECT_NE(study.Text().find("drained critical state as I -> 0, E = 500 MPa, χ = 0.5, k_t/k_n = "
                              "0.3, f = 0.3: M = 0.920"),
            std::string::npos)
      << study.Text();
  // A malformed number names the file, its line and the column.
  std::string text;
  {
    std::ifstream in(dir / kRateDrainedStatesFile);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const size_t at = text.find(",0.3,5,");  // time-step fraction, radial stress
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 7, ",0.3,five,");
  std::ofstream(dir / kRateDrainedStatesFile) << text;
  try {
    ReadDrainedStates(dir.string());
    FAIL() << "accepted a malformed number";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(kRateDrainedStatesFile), std::string::npos) << message;
    EXPECT_NE(message.find("line 3"), std::string::npos) << message;
    EXPECT_NE(message.find("radial_stress_kpa"), std::string::npos) << message;
  }
}

TEST(ReadRateStates, MalformedNumbersNameTheFileAndLine) {
  const fs::path dir = Folder("read");
  EXPECT_TRUE(ReadRateStates(dir.string()).empty());  // no file: no rate study
  const std::string header =
      "replicate,case_name,stage,kind,status,youngs_modulus_mpa,psi_epsilon_deg,start_p_kpa,"
      "rate_rule,inertial_number_target,stretching_rate_per_s,p_kpa,e,ln_1_plus_e,"
      "psi_sigma_deg,q_over_p,ocr,inertial_number_dmin,inertial_number_dmax,stiffness_number,"
      "flags\n";
  std::ofstream(dir / kRateStatesFile)
      << "# comment\n"
      << header
      << "1,nc20_psi90_I0.001,psi90,csl,detected,500,90,20,inertial,0.001,167,6,0.7,0.53,25.4,"
         "1.0,1.9,0.0002,0.001,41666,\n";
  const std::vector<RateState> states = ReadRateStates(dir.string());
  ASSERT_EQ(states.size(), 1u);
  EXPECT_EQ(states[0].rule, dem::RateRule::kInertial);
  EXPECT_DOUBLE_EQ(states[0].rate(), 0.001);
  EXPECT_DOUBLE_EQ(states[0].start_p_kpa, 20);
  std::ofstream(dir / kRateStatesFile)
      << header
      << "1,c,s,csl,detected,500,90,twenty,inertial,0.001,167,6,0.7,0.53,25.4,1.0,1.9,0.0002,"
         "0.001,41666,\n";
  try {
    ReadRateStates(dir.string());
    FAIL() << "accepted a malformed number";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("line 2"), std::string::npos) << message;
    EXPECT_NE(message.find("start_p_kpa"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace granasym::analysis
