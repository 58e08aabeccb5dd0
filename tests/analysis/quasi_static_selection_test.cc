#include "analysis/quasi_static_selection.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tests/analysis/rate_states_fixture.h"

namespace granasym::analysis {
namespace {
namespace fs = std::filesystem;
using rate_fixture::CriticalStates;
using rate_fixture::DrainedStates;

TEST(QuasiStatic, TheSmallestRateWithACslFromTwoStartsIsTheCalibratedSet) {
  std::vector<RateState> states = CriticalStates();
  for (RateState& s : states) {
    s.case_name = fmt::format("nc{:g}_psi90_{}{:g}", s.start_p_kpa,
                              s.rule == dem::RateRule::kInertial ? "I" : "D", s.rate());
  }
  // At 3e-4 only one start keeps usable states: 1e-3 is the smallest with a CSL.
  for (RateState& s : states) {
    if (s.rule == dem::RateRule::kInertial && s.inertial_number == 3e-4 && s.start_p_kpa == 20) {
      s.flags = "gas";
    }
  }
  RateStudy study = RateStudy::Analyse(states);
  // The drained cases: at the slowest axial rate of each σ_r, except at
  // 20 kPa, where the slowest has no usable state (a gas) and the next is
  // taken; another modulus stays out.
  std::vector<DrainedState> drained = DrainedStates(0.0);
  for (DrainedState& s : drained) {
    if (s.radial_stress_kpa == 20 && s.inertial_number_dmax == 3e-4) s.flags = "gas";
  }
  DrainedState soft = drained.front();
  soft.youngs_modulus_mpa = 100;
  soft.case_name = "nc5_drained_soft";
  drained.push_back(soft);
  study.drained = DrainedStudy::Analyse(drained, study.options);
  const QuasiStaticSelection chosen = SelectQuasiStatic(study);
  ASSERT_TRUE(chosen.valid()) << chosen.reason;
  EXPECT_EQ(chosen.inertial_number, 1e-3);
  EXPECT_EQ(chosen.youngs_modulus_mpa, 500);
  EXPECT_EQ(chosen.cases, (std::vector<std::string>{"nc20_psi90_I0.001", "nc100_psi90_I0.001"}));
  EXPECT_EQ(chosen.drained_cases,
            (std::vector<std::string>{"nc5_drained_I0.0003", "nc20_drained_I0.001",
                                      "nc100_drained_I0.0003", "nc500_drained_I0.0003"}));
  // Asked for: any I* the study has, also one without a CSL.
  EXPECT_EQ(SelectQuasiStatic(study, 3e-4).cases.size(), 2u);
  const QuasiStaticSelection none = SelectQuasiStatic(study, 0.5);
  EXPECT_FALSE(none.valid());
  EXPECT_NE(none.reason.find("no rate case runs at I* = 0.5"), std::string::npos) << none.reason;
  EXPECT_NE(none.reason.find("0.0003, 0.001, 0.003, 0.01"), std::string::npos) << none.reason;
  // Written and read back.
  const fs::path dir = fs::temp_directory_path() / "granasym_tests" / "rate_study" / "selection";
  fs::remove_all(dir);
  EXPECT_FALSE(ReadQuasiStaticSelection(dir.string()).has_value());
  WriteQuasiStaticSelection(dir.string(), chosen);
  const std::optional<QuasiStaticSelection> back = ReadQuasiStaticSelection(dir.string());
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->inertial_number, 1e-3);
  EXPECT_EQ(back->cases, chosen.cases);
  EXPECT_EQ(back->drained_cases, chosen.drained_cases);
  EXPECT_TRUE(back->other_cases.empty());
}

// A study without ψ_ε = 90° rate cases whose critical state comes from its
// drained cases (studies/programmes/quasi_static_extension.toml, issue 39
// §3): the smallest I* of its rate cases is the set, with the drained cases;
// the other cases of the set are written and read back. Without drained
// cases there is no critical state and no set.
TEST(QuasiStatic, AStudyOfExtensionSweepsTakesItsSmallestRateWithTheDrainedCases) {
  std::vector<RateState> states;
  for (RateState s : rate_fixture::ExtensionSweep()) {
    if (s.psi_epsilon_deg == 90) continue;
    s.case_name = fmt::format("nc{:g}_psi{:g}_I0.003", s.start_p_kpa, s.psi_epsilon_deg);
    states.push_back(s);
    s.inertial_number = 1e-3;  // and a slower sweep
    s.case_name = fmt::format("nc{:g}_psi{:g}_I0.001", s.start_p_kpa, s.psi_epsilon_deg);
    states.push_back(s);
  }
  RateStudy study = RateStudy::Analyse(states);
  const QuasiStaticSelection without = SelectQuasiStatic(study);
  EXPECT_FALSE(without.valid());
  EXPECT_NE(without.reason.find("from two starts at E = 500 MPa"), std::string::npos)
      << without.reason;
  study.drained = DrainedStudy::Analyse(DrainedStates(0.0), study.options);
  QuasiStaticSelection chosen = SelectQuasiStatic(study);
  ASSERT_TRUE(chosen.valid()) << chosen.reason;
  EXPECT_EQ(chosen.inertial_number, 1e-3);
  EXPECT_EQ(chosen.cases.size(), 7u);  // 100, 110, 120, 130° from 100 kPa, 100-120° from 20
  for (const std::string& name : chosen.cases) {
    EXPECT_NE(name.find("_I0.001"), std::string::npos) << name;
  }
  EXPECT_EQ(chosen.drained_cases.size(), 4u);  // the slowest rate of each σ_r
  chosen.other_cases = {"ncl_qs", "nc100_psi70_I0.001"};
  EXPECT_EQ(chosen.AllCases().size(), 13u);
  EXPECT_NE(SelectionText(chosen).find("and 2 other cases at I* or slower (ncl_qs, "
                                       "nc100_psi70_I0.001), E = 500 MPa"),
            std::string::npos)
      << SelectionText(chosen);
  const fs::path dir = fs::temp_directory_path() / "granasym_tests" / "rate_study" / "others";
  fs::remove_all(dir);
  WriteQuasiStaticSelection(dir.string(), chosen);
  const std::optional<QuasiStaticSelection> back = ReadQuasiStaticSelection(dir.string());
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->other_cases, chosen.other_cases);
  EXPECT_EQ(back->AllCases(), chosen.AllCases());
  // A study with ψ_ε = 90° rate cases keeps the rule of a CSL from two starts.
  std::vector<RateState> with_csl = states;
  RateState isochoric = states.front();
  isochoric.psi_epsilon_deg = 90;
  isochoric.flags = "gas";
  with_csl.push_back(isochoric);
  RateStudy csl = RateStudy::Analyse(with_csl);
  csl.drained = study.drained;
  EXPECT_FALSE(SelectQuasiStatic(csl).valid());
}

}  // namespace
}  // namespace granasym::analysis
