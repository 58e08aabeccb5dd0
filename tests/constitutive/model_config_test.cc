// Model and test files: validation messages and the HDF5 result layout.
#include "constitutive/model_config.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "common/error.h"

namespace granasym {
namespace {

const char* kClay = R"(
[model]
kind = "hypoplastic_clay"
phi_c_deg = 22.6
lambda_star = 0.11
kappa_star = 0.016
n_intercept = 1.375
r = 0.4
)";

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  return text;
}

void ExpectRejected(const std::string& text, const std::string& key) {
  const ConfigTable root = ConfigTable::ParseString(text, "model.toml");
  try {
    ReadModel(root.GetTable("model"));
    FAIL() << "accepted a bad " << key;
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("model.toml"), std::string::npos) << message;
    EXPECT_NE(message.find(key), std::string::npos) << message;
  }
}

TEST(ModelConfig, ReadsAValidHypoplasticModel) {
  const ConfigTable root = ConfigTable::ParseString(kClay, "model.toml");
  const auto model = ReadModel(root.GetTable("model"));
  EXPECT_EQ(model->kind(), ModelKind::kHypoplasticClay);
  EXPECT_NO_THROW(root.CheckNoUnknownKeys());
}

TEST(ModelConfig, RejectsBadParameterFiles) {
  ExpectRejected(Replace(kClay, "kappa_star = 0.016", "kappa_star = 0.11"), "kappa_star");
  ExpectRejected(Replace(kClay, "phi_c_deg = 22.6", "phi_c_deg = 90.5"), "phi_c_deg");
  ExpectRejected(Replace(kClay, "r = 0.4", "r = 0.0"), "r");
  ExpectRejected(Replace(kClay, "r = 0.4", "r = -1.0"), "r");
  const std::string cam_clay = R"(
[model]
kind = "modified_cam_clay"
critical_state_ratio = 0.9
lambda_star = 0.1
kappa_star = 0.12
n_intercept = 1.4
)";
  ExpectRejected(cam_clay, "kappa_star");
  ExpectRejected(Replace(cam_clay, "critical_state_ratio = 0.9", "phi_c_deg = 25.0\ncritical_state_ratio = 0.9"),
                 "critical_state_ratio");
}

TEST(ModelConfig, UnknownKeysAreNamed) {
  const ConfigTable root =
      ConfigTable::ParseString(Replace(kClay, "r = 0.4", "r = 0.4\nlambda = 0.1"), "model.toml");
  ReadModel(root.GetTable("model"));
  EXPECT_THROW(root.CheckNoUnknownKeys(), InputError);
}

TEST(ModelConfig, RunsATestFileAndWritesUnits) {
  const std::string text = std::string(kClay) + R"(
[initial]
mean_stress_kpa = 100.0
ocr = 2.0

[[stage]]
type = "mixed"
rate = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]
stress_controlled = [1, 2]
duration_s = 0.1
[stage.stop]
axial_strain = 0.05
)";
  const ConfigTable root = ConfigTable::ParseString(text, "test.toml");
  const auto model = ReadModel(root.GetTable("model"));
  const ModelState initial = ReadInitialState(*model, root.GetTable("initial"));
  const std::vector<LoadingStage> stages = ReadStages(root);
  root.CheckNoUnknownKeys();
  ASSERT_EQ(stages.size(), 1u);
  EXPECT_EQ(stages[0].control[1], ComponentControl::kStressRate);
  const ElementTestResult result = ElementTest(*model, ElementTestOptions()).Run(initial, stages);
  ASSERT_TRUE(result.summary.success()) << result.summary.Report();
  EXPECT_NEAR(result.history.back().strain[0], 0.05, 1e-9);  // exact stop
  EXPECT_NEAR(RecordStress(result.history.back()).radial, 100.0, 1e-6);  // radial stress held

  const std::string path =
      (std::filesystem::temp_directory_path() / "granasym_model_config_test.h5").string();
  {
    Hdf5File file = Hdf5File::CreateAtomic(path);
    WriteElementTestResult(*model, result, "/element_test", &file);
    file.Commit();
  }
  const Hdf5File file = Hdf5File::OpenRead(path);
  EXPECT_EQ(file.ReadStringAttribute("/element_test/mean_stress", "units"), "kPa");
  EXPECT_EQ(file.ReadStringAttribute("/element_test/psi_sigma", "units"), "rad");
  EXPECT_EQ(file.ReadDoubles("/element_test/mean_stress").size(), result.history.size());
  EXPECT_EQ(file.ReadStringAttribute("/element_test", "termination"), "reached_end");
  std::remove(path.c_str());
}

}  // namespace
}  // namespace granasym
