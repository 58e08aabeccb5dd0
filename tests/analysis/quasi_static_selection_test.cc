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
}

}  // namespace
}  // namespace granasym::analysis
