#include "dem/scene.h"

#include <gtest/gtest.h>

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
