// Model and test files: validation messages and the HDF5 result layout.
#include "constitutive/model_config.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "common/csv_table.h"
#include "common/error.h"
#include "tests/common/enum_spellings.h"

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

TEST(ModelConfig, NamesAreSpelledAsInFiles) {
  ExpectSpellings<ModelKind>({{ModelKind::kHypoplasticClay, "hypoplastic_clay"},
                              {ModelKind::kModifiedCamClay, "modified_cam_clay"},
                              {ModelKind::kHypoplasticSand, "hypoplastic_sand"}});
  ExpectSpellings<LoadingStageType>(
      {{LoadingStageType::kProportional, "proportional"},
       {LoadingStageType::kConstantRadialStress, "constant_radial_stress"},
       {LoadingStageType::kIsochoric, "isochoric"},
       {LoadingStageType::kOedometric, "oedometric"},
       {LoadingStageType::kIsotropic, "isotropic"},
       {LoadingStageType::kMixed, "mixed"}});
}

TEST(ModelConfig, UnknownNamesListTheAllowedOnes) {
  ExpectRejected(Replace(kClay, "kind = \"hypoplastic_clay\"", "kind = \"clay\""),
                 "key 'model.kind' = 'clay' is not valid: expected hypoplastic_clay, "
                 "modified_cam_clay or hypoplastic_sand");
  const ConfigTable integration =
      ConfigTable::ParseString("[integration]\nintegrator = \"euler\"\n", "test.toml")
          .GetTable("integration");
  try {
    ReadElementTestOptions(integration);
    FAIL() << "accepted integrator = euler";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("test.toml"), std::string::npos) << message;
    EXPECT_NE(message.find("'integration.integrator' = 'euler'"), std::string::npos) << message;
    EXPECT_NE(message.find("cvode_bdf, cvode_adams, arkode_erk, arkode_dirk or rkf23"),
              std::string::npos)
        << message;
  }
}

// The stop keys are the StopKind names, the mean stress with its unit.
TEST(ModelConfig, ReadsEveryStopKey) {
  const ConfigTable root = ConfigTable::ParseString(R"(
[[stage]]
type = "isochoric"
[stage.stop]
mean_stress_kpa = 50.0
axial_strain = 0.1
volumetric_strain = 0.2
shear_strain = 0.3
strain_path = 0.4
stress_ratio = 0.5
asymptote = 1e-6
)",
                                                    "test.toml");
  const std::vector<LoadingStage> stages = ReadStages(root);
  EXPECT_NO_THROW(root.CheckNoUnknownKeys());
  ASSERT_EQ(stages.size(), 1u);
  const std::vector<StopCondition>& stops = stages[0].stops;
  ASSERT_EQ(stops.size(), 7u);
  const std::vector<std::pair<StopKind, double>> expected = {
      {StopKind::kMeanStress, 50.0},      {StopKind::kAxialStrain, 0.1},
      {StopKind::kVolumetricStrain, 0.2}, {StopKind::kShearStrain, 0.3},
      {StopKind::kStrainPath, 0.4},       {StopKind::kStressRatio, 0.5},
      {StopKind::kAsymptote, 1e-6}};
  for (size_t i = 0; i < stops.size(); ++i) {
    EXPECT_EQ(stops[i].kind, expected[i].first) << i;
    EXPECT_DOUBLE_EQ(stops[i].value, expected[i].second) << i;
  }
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
  ExpectRejected(Replace(cam_clay, "critical_state_ratio = 0.9",
                         "phi_c_deg = 25.0\ncritical_state_ratio = 0.9"),
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
  EXPECT_NEAR(result.history.back().strain[0], 0.05, 1e-9);              // exact stop
  EXPECT_NEAR(RecordStress(result.history.back()).radial, 100.0, 1e-6);  // radial stress held

  const std::string path =
      (std::filesystem::temp_directory_path() / "granasym_model_config_test.h5").string();
  {
    Hdf5File file = Hdf5File::CreateAtomic(path);
    WriteElementTestResult(*model, result, "/element_test", &file);
    file.Commit();
  }
  const Hdf5File file = Hdf5File::OpenRead(path);
  // The names and units of common/quantity_names.h, angles in degrees.
  EXPECT_EQ(file.ReadStringAttribute("/element_test/time_s", "units"), "s");
  EXPECT_EQ(file.ReadStringAttribute("/element_test/p_kpa", "units"), "kPa");
  EXPECT_EQ(file.ReadStringAttribute("/element_test/q_kpa", "units"), "kPa");
  EXPECT_EQ(file.ReadStringAttribute("/element_test/e", "units"), "1");
  EXPECT_EQ(file.ReadStringAttribute("/element_test/psi_sigma_deg", "units"), "deg");
  EXPECT_EQ(file.ReadStringAttribute("/element_test/psi_epsilon_deg", "units"), "deg");
  const std::vector<double> p = file.ReadDoubles("/element_test/p_kpa");
  const std::vector<double> psi_sigma = file.ReadDoubles("/element_test/psi_sigma_deg");
  ASSERT_EQ(p.size(), result.history.size());
  ASSERT_EQ(psi_sigma.size(), result.history.size());
  EXPECT_EQ(p.back(), RecordStress(result.history.back()).mean());
  EXPECT_EQ(psi_sigma.back(), RecordStress(result.history.back()).psi() / kDegree);
  EXPECT_GT(psi_sigma.back(), 1.0);  // degrees, not radians
  EXPECT_EQ(file.ReadStringAttribute("/element_test", "termination"), "reached_end");
  std::remove(path.c_str());

  // The CSV: the same names, and the same numbers.
  const std::string csv =
      (std::filesystem::temp_directory_path() / "granasym_model_config_test.csv").string();
  WriteElementTestCsv(result, csv);
  const CsvTable table = CsvTable::ReadFile(csv);
  EXPECT_EQ(table.columns,
            (std::vector<std::string>{"time_s", "sigma_a_kpa", "sigma_r_kpa", "p_kpa", "q_kpa", "e",
                                      "eps_a", "eps_r", "strain_path", "psi_sigma_deg",
                                      "psi_epsilon_deg", "ocr"}));
  ASSERT_EQ(table.rows.size(), result.history.size());
  EXPECT_EQ(table.rows.back()[table.Column("e")], result.history.back().void_ratio);
  EXPECT_EQ(table.rows.back()[table.Column("psi_sigma_deg")], psi_sigma.back());
  std::remove(csv.c_str());
}

const char* kSand = R"(
[model]
kind = "hypoplastic_sand"
phi_c_deg = 33.0
h_s_kpa = 1.0e6
n = 0.25
e_d0 = 0.55
e_c0 = 0.95
e_i0 = 1.05
alpha = 0.25
beta = 1.5
)";

// The message names the file, every key in `keys` and the bad value.
void ExpectSandRejected(const std::string& text, const std::vector<std::string>& keys,
                        const std::string& value) {
  const ConfigTable root = ConfigTable::ParseString(text, "sand.toml");
  try {
    ReadModel(root.GetTable("model"));
    FAIL() << "accepted a bad " << keys.front();
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("sand.toml"), std::string::npos) << message;
    for (const std::string& key : keys) EXPECT_NE(message.find(key), std::string::npos) << message;
    EXPECT_NE(message.find(value), std::string::npos) << message;
  }
}

TEST(ModelConfig, ReadsAValidHypoplasticSandModel) {
  const ConfigTable root = ConfigTable::ParseString(kSand, "sand.toml");
  const auto model = ReadModel(root.GetTable("model"));
  EXPECT_EQ(model->kind(), ModelKind::kHypoplasticSand);
  EXPECT_NO_THROW(root.CheckNoUnknownKeys());
  // Every parameter reaches the model (the reference set, Hochstetten sand).
  EXPECT_EQ(model->Describe(),
            "hypoplastic_sand phi_c=33 deg h_s=1e+06 kPa n=0.25 e_d0=0.55 e_c0=0.95 e_i0=1.05 "
            "alpha=0.25 beta=1.5 (a=2.76072)");
  // minimum_mean_stress_kpa: 1e-9 by default, here 0.01, so p = 0.005 kPa is outside.
  const ModelState low = model->MakeState(AxisymmetricStressTensor(0.005, 0.0), 0.9);
  std::string why;
  EXPECT_TRUE(model->IsAdmissible(low, &why)) << why;
  const ConfigTable with_minimum = ConfigTable::ParseString(
      std::string(kSand) + "minimum_mean_stress_kpa = 0.01\n", "sand.toml");
  EXPECT_FALSE(ReadModel(with_minimum.GetTable("model"))->IsAdmissible(low, &why));
  EXPECT_NE(why.find("0.01"), std::string::npos) << why;
}

TEST(ModelConfig, RejectsBadSandParameterFiles) {
  ExpectSandRejected(Replace(kSand, "phi_c_deg = 33.0", "phi_c_deg = 0.0"), {"phi_c_deg"}, "0");
  ExpectSandRejected(Replace(kSand, "h_s_kpa = 1.0e6", "h_s_kpa = -5.0"), {"h_s_kpa"}, "-5");
  ExpectSandRejected(Replace(kSand, "n = 0.25", "n = 1.2"), {"n"}, "1.2");
  ExpectSandRejected(Replace(kSand, "e_d0 = 0.55", "e_d0 = -0.1"), {"e_d0"}, "-0.1");
  ExpectSandRejected(Replace(kSand, "alpha = 0.25", "alpha = 0.0"), {"alpha"}, "0");
  ExpectSandRejected(Replace(kSand, "beta = 1.5", "beta = -1.0"), {"beta"}, "-1");
  ExpectSandRejected(Replace(kSand, "beta = 1.5", "beta = 1.5\nminimum_mean_stress_kpa = 0.0"),
                     {"minimum_mean_stress_kpa"}, "0");
  // The ordering e_d0 < e_c0 < e_i0 names both keys of the broken pair.
  ExpectSandRejected(Replace(kSand, "e_d0 = 0.55", "e_d0 = 0.97"), {"e_c0", "e_d0"}, "0.97");
  ExpectSandRejected(Replace(kSand, "e_i0 = 1.05", "e_i0 = 0.9"), {"e_i0", "e_c0"}, "0.9");
  // α = 4 makes 3 + a² − a√3 ((e_i0 − e_d0)/(e_c0 − e_d0))^α negative: f_b < 0.
  ExpectSandRejected(Replace(kSand, "alpha = 0.25", "alpha = 4.0"), {"alpha", "f_b"}, "4");
  // A missing key is named.
  ExpectSandRejected(Replace(kSand, "e_c0 = 0.95\n", ""), {"e_c0"}, "e_c0");
}

TEST(ModelConfig, RunsASandTestFile) {
  const std::string text = std::string(kSand) + R"(
[initial]
mean_stress_kpa = 100.0
void_ratio = 0.7

[[stage]]
type = "isochoric"
axial_rate = 1.0
duration_s = 0.05
)";
  const ConfigTable root = ConfigTable::ParseString(text, "test.toml");
  const auto model = ReadModel(root.GetTable("model"));
  const ModelState initial = ReadInitialState(*model, root.GetTable("initial"));
  const std::vector<LoadingStage> stages = ReadStages(root);
  root.CheckNoUnknownKeys();
  const ElementTestResult result = ElementTest(*model, ElementTestOptions()).Run(initial, stages);
  ASSERT_TRUE(result.summary.success()) << result.summary.Report();
  EXPECT_NEAR(result.history.back().void_ratio, 0.7, 1e-9);
  // Isochoric shear of dense sand (e_c(100 kPa) = 0.83) raises p.
  EXPECT_GT(RecordStress(result.history.back()).mean(), 100.0);
  // A state at or below e_d(p) is rejected at the boundary, naming the table.
  const ConfigTable dense =
      ConfigTable::ParseString(Replace(text, "void_ratio = 0.7", "void_ratio = 0.3"), "test.toml");
  EXPECT_THROW(ReadInitialState(*model, dense.GetTable("initial")), InputError);
}

}  // namespace
}  // namespace granasym
