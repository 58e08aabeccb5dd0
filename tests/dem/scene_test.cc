#include "dem/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>

#include "common/error.h"
#include "test_util.h"

namespace granasym::dem {
namespace {

const char* kValid = R"(
[sample.generate]
count = 1000
cell_size_mm = 5.8
[material]
youngs_modulus_mpa = 500.0
friction_angle_rad = 0.5
[numerics]
time_step_s = 1.2e-7
[[stage]]
name = "ncl"
psi_epsilon_deg = 0.0
stretching_rate = 167.0
[stage.stop]
mean_stress_kpa = 100.0
)";

std::string ErrorOf(const std::string& text) {
  try {
    const Scene scene = Scene::Parse(text, "bad.toml", "");
    scene.TimeStep(scene.BuildSample(nullptr));
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

void ExpectMentions(const std::string& message, std::initializer_list<const char*> parts) {
  ASSERT_FALSE(message.empty()) << "no error was raised";
  for (const char* part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
}

TEST(Scene, ValidSceneParsesWithUnitsConverted) {
  const Scene scene = Scene::Parse(kValid, "good.toml", "");
  EXPECT_DOUBLE_EQ(scene.material.youngs_modulus, 500e6);
  ASSERT_EQ(scene.stages.size(), 1u);
  EXPECT_EQ(scene.stages[0].type(), "strain_path");
  EXPECT_DOUBLE_EQ(*scene.stages[0].stop.mean_stress_kpa, 100.0);
  EXPECT_EQ(ErrorOf(kValid), "");
}

TEST(Scene, UnknownKeyIsRejectedWithTheValidKeys) {
  ExpectMentions(ErrorOf(Replace(kValid, "friction_angle_rad", "friction_angle")),
                 {"bad.toml", "material.friction_angle", "friction_angle_rad"});
}

TEST(Scene, StopOnLiquefactionNeedsAnotherConditionAndADetector) {
  // Alone it may never end the stage.
  ExpectMentions(ErrorOf(Replace(kValid, "mean_stress_kpa = 100.0", "liquefied = true")),
                 {"bad.toml", "stop.liquefied", "not enough", "strain_norm"});
  // Rest stages have no asymptote detector (and so no window).
  const std::string rest = Replace(Replace(kValid, "psi_epsilon_deg = 0.0\nstretching_rate = 167.0",
                                           "type = \"rest\"\nmean_stress_kpa = 100.0"),
                                   "[stage.stop]\nmean_stress_kpa = 100.0",
                                   "[stage.stop]\nsteps = 10\nliquefied = true");
  ExpectMentions(ErrorOf(rest), {"stop.liquefied", "rest", "no asymptote detector"});
  const Scene scene = Scene::Parse(
      Replace(kValid, "mean_stress_kpa = 100.0", "mean_stress_kpa = 100.0\nliquefied = true"),
      "good.toml", "");
  EXPECT_TRUE(scene.stages[0].stop.liquefied);
  EXPECT_TRUE(scene.stages[0].detect_asymptote);
  EXPECT_FALSE(scene.stages[0].stop.liquefied_strain.has_value());
  // Its own gas window: positive, and only with liquefied = true.
  const Scene windowed = Scene::Parse(Replace(kValid, "mean_stress_kpa = 100.0",
                                              "mean_stress_kpa = 100.0\nliquefied = true\n"
                                              "liquefied_strain = 0.02"),
                                      "good.toml", "");
  EXPECT_EQ(windowed.stages[0].stop.liquefied_strain, 0.02);
  ExpectMentions(ErrorOf(Replace(kValid, "mean_stress_kpa = 100.0",
                                 "mean_stress_kpa = 100.0\nliquefied_strain = 0.02")),
                 {"bad.toml", "stop.liquefied_strain", "liquefied = true"});
  ExpectMentions(
      ErrorOf(Replace(kValid, "mean_stress_kpa = 100.0",
                      "mean_stress_kpa = 100.0\nliquefied = true\nliquefied_strain = 0")),
      {"bad.toml", "stop.liquefied_strain", "0"});
}

TEST(Scene, WrongTypeIsRejected) {
  ExpectMentions(ErrorOf(Replace(kValid, "stretching_rate = 167.0", "stretching_rate = 'fast'")),
                 {"stage[0].stretching_rate", "expected a number"});
}

TEST(Scene, NonPositiveModulusAndSizeAreRejected) {
  ExpectMentions(ErrorOf(Replace(kValid, "youngs_modulus_mpa = 500.0", "youngs_modulus_mpa = -1")),
                 {"material.youngs_modulus_mpa", "-1", "in [0.001, 10000000]"});
  ExpectMentions(ErrorOf(Replace(kValid, "cell_size_mm = 5.8", "cell_size_mm = 0")),
                 {"sample.generate.cell_size_mm", "in [0.001, 1000000]"});
}

TEST(Scene, TimeStepAboveTheStabilityLimitIsRejectedWithTheLimit) {
  ExpectMentions(ErrorOf(Replace(kValid, "time_step_s = 1.2e-7", "time_step_s = 1e-6")),
                 {"numerics.time_step_s", "stability limit", "6."});
}

TEST(Scene, WithoutAFixedStepTheTimeStepIsAdaptive) {
  const std::string adaptive_text =
      Replace(kValid, "time_step_s = 1.2e-7",
              "time_step_fraction = 0.2\ntime_step_check_interval = 25\nmax_time_step_s = 1e-7");
  const Scene adaptive = Scene::Parse(adaptive_text, "adaptive.toml", "");
  ASSERT_TRUE(adaptive.adaptive());
  EXPECT_EQ(adaptive.adaptive_time_step.fraction, 0.2);
  EXPECT_EQ(adaptive.adaptive_time_step.check_interval, 25);
  EXPECT_EQ(adaptive.adaptive_time_step.max_time_step, 1e-7);
  // The largest step: f t_c(min) = 0.2 · 1.05e-6 s capped at 1e-7 s.
  EXPECT_EQ(adaptive.TimeStep(adaptive.BuildSample(nullptr)), 1e-7);
  const std::string canonical = adaptive.Canonical();
  EXPECT_NE(canonical.find("numerics.time_step_check_interval"), std::string::npos) << canonical;
  EXPECT_NE(canonical.find("numerics.max_time_step_s"), std::string::npos) << canonical;
  EXPECT_EQ(canonical.find("numerics.time_step_s"), std::string::npos) << canonical;
  // Defaults: 0.1 of the shortest duration, every 100 steps, no cap.
  const Scene defaults = Scene::Parse(Replace(kValid, "time_step_s = 1.2e-7", ""), "d.toml", "");
  ASSERT_TRUE(defaults.adaptive());
  EXPECT_EQ(defaults.adaptive_time_step.fraction, 0.1);
  EXPECT_EQ(defaults.adaptive_time_step.check_interval, 100);
  EXPECT_FALSE(std::isfinite(defaults.adaptive_time_step.max_time_step));
  EXPECT_EQ(defaults.Canonical().find("max_time_step_s"), std::string::npos);
  const Scene fixed = Scene::Parse(kValid, "fixed.toml", "");
  EXPECT_FALSE(fixed.adaptive());
  EXPECT_EQ(fixed.Canonical().find("time_step_check_interval"), std::string::npos);
}

TEST(Scene, TheAdaptiveKeysOfAFixedStepAreRejected) {
  ExpectMentions(ErrorOf(Replace(kValid, "time_step_s = 1.2e-7",
                                 "time_step_s = 1.2e-7\ntime_step_fraction = 0.1")),
                 {"numerics.time_step_s", "time_step_fraction", "give one of them"});
  ExpectMentions(ErrorOf(Replace(kValid, "time_step_s = 1.2e-7",
                                 "time_step_s = 1.2e-7\ntime_step_check_interval = 10")),
                 {"numerics.time_step_check_interval", "adaptive", "time_step_s"});
  ExpectMentions(ErrorOf(Replace(kValid, "time_step_s = 1.2e-7",
                                 "time_step_s = 1.2e-7\nmax_time_step_s = 1e-7")),
                 {"numerics.max_time_step_s", "adaptive"});
}

TEST(Scene, AdaptiveKeysOutOfRangeAreRejectedWithTheRange) {
  ExpectMentions(ErrorOf(Replace(kValid, "time_step_s = 1.2e-7", "time_step_fraction = 0.7")),
                 {"numerics.time_step_fraction", "0.7", "[0.0001, 0.63"});
  ExpectMentions(ErrorOf(Replace(kValid, "time_step_s = 1.2e-7", "time_step_check_interval = 0")),
                 {"numerics.time_step_check_interval", "= 0", "in [1, 1000000]"});
  ExpectMentions(ErrorOf(Replace(kValid, "time_step_s = 1.2e-7", "max_time_step_s = 2.0")),
                 {"numerics.max_time_step_s", "= 2", "in (0, 1)"});
  // Below 1e-4 of the smallest contact duration (1.047e-6 s): it resolves nothing more.
  ExpectMentions(ErrorOf(Replace(kValid, "time_step_s = 1.2e-7", "max_time_step_s = 1e-11")),
                 {"numerics.max_time_step_s", "1e-11", "below 0.0001", "1.047e-06"});
}

TEST(Scene, AFractionBeyondTheLeapfrogLimitOfTheContactsIsRejectedWithTheLimit) {
  // The paper's linear law with friction: 2/(π sqrt(1.05)) = 0.621 of t_c.
  ExpectMentions(ErrorOf(Replace(kValid, "time_step_s = 1.2e-7", "time_step_fraction = 0.63")),
                 {"numerics.time_step_fraction", "0.63", "stability limit 0.6213"});
  // Hertz–Mindlin with friction: k_t/k_n = 6/7 at ν = 0.25, 2/(π sqrt(3)) = 0.3676.
  const std::string hertz =
      Replace(kValid, "youngs_modulus_mpa = 500.0",
              "youngs_modulus_mpa = 500.0\ncontact_law = 'hertz_mindlin'\npoissons_ratio = 0.25");
  ExpectMentions(ErrorOf(Replace(hertz, "time_step_s = 1.2e-7", "time_step_fraction = 0.4")),
                 {"numerics.time_step_fraction", "0.4", "stability limit 0.3676"});
  EXPECT_EQ(ErrorOf(Replace(hertz, "time_step_s = 1.2e-7", "time_step_fraction = 0.35")), "");
}

TEST(Scene, NonMonotonicGsdIsRejectedNamingTheRow) {
  const std::string gsd = testing::TempPath("bad_gsd.csv");
  std::ofstream(gsd) << "diameter_mm,percent_passing_by_mass\n0.2,0\n0.4,50\n0.6,40\n1.0,100\n";
  const std::string text =
      Replace(kValid, "cell_size_mm = 5.8", "cell_size_mm = 5.8\ngsd = '" + gsd + "'");
  ExpectMentions(ErrorOf(text), {"bad_gsd.csv", "line 4", "non-decreasing"});
}

TEST(Scene, StageWithoutStopConditionIsRejected) {
  ExpectMentions(ErrorOf(Replace(kValid, "mean_stress_kpa = 100.0", "")), {"no stop condition"});
}

TEST(Scene, AngleOutOfRangeIsRejected) {
  ExpectMentions(ErrorOf(Replace(kValid, "psi_epsilon_deg = 0.0", "psi_epsilon_deg = 200.0")),
                 {"psi_epsilon_deg", "[-180, 180]"});
}

TEST(Scene, UnknownStageTypeIsRejected) {
  ExpectMentions(ErrorOf(Replace(kValid, "name = \"ncl\"", "name = \"ncl\"\ntype = \"shear\"")),
                 {"stage[0].type", "strain_path", "triaxial", "rest"});
}

TEST(Scene, MissingPackingFileIsRejected) {
  const std::string text = Replace(kValid, "[sample.generate]\ncount = 1000\ncell_size_mm = 5.8",
                                   "[sample]\npacking = 'no_such_packing.txt'");
  ExpectMentions(ErrorOf(text), {"no_such_packing.txt"});
}

TEST(Scene, DefaultOptionsAreValid) {
  std::string why;
  EXPECT_TRUE(GenerationOptions{}.IsValid(&why)) << why;
}

}  // namespace
}  // namespace granasym::dem
