// The calibration of a study, built in code: the same configuration as the
// calibration file that `study calibrate` wrote and read back before, and a
// file that reads back as it.
#ifdef GRANASYM_ANALYSIS_HAS_CALIBRATION  // a build with the models (GRANASYM_BUILD_MODELS)
#include "analysis/study_calibration.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "common/config.h"
#include "common/text_file.h"
#include "tests/calibration/same_config.h"

namespace granasym::analysis {
namespace {
namespace fs = std::filesystem;

// The file that `study calibrate` generated for a study with an NCL case.
const char* kStudyFile = R"(
[model]
kind = "hypoplastic_clay"

[[dataset]]
name = "study"
study = "../.."
exclude_flags = ["overlap_above_10pct", "gas"]
psi_sigma_uncertainty_deg = 0.5
ln_1_plus_e_uncertainty = 0.002
kinds = ["ncl", "csl", "compression", "extension", "triaxial"]
statuses = ["detected"]
ncl_references = ["ncl"]

[fitter]
method = "ceres"
fix_undetermined = true

[output]
hdf5 = "calibration.h5"
summary = "summary.txt"
plot_data = "plot_data"
status = "fit_status.toml"
)";

// ... and for a rate study's quasi-static set.
const char* kRateFile = R"(
[model]
kind = "hypoplastic_sand"

[[dataset]]
name = "quasi_static_ncl"
study = "../.."
exclude_flags = ["overlap_above_10pct", "gas"]
psi_sigma_uncertainty_deg = 0.5
ln_1_plus_e_uncertainty = 0.002
kinds = ["ncl"]
statuses = ["detected", "drifting"]
cases = ["nc100_psi0_I0.001", "nc100_psi90_I0.001"]

[[dataset]]
name = "quasi_static"
study = "../.."
exclude_flags = ["overlap_above_10pct", "gas"]
psi_sigma_uncertainty_deg = 0.5
ln_1_plus_e_uncertainty = 0.002
kinds = ["csl", "compression", "extension", "triaxial"]
statuses = ["detected"]
cases = ["nc100_psi0_I0.001", "nc100_psi90_I0.001", "tx100_ea0.01"]

[fitter]
method = "both"
fix_undetermined = true

[output]
hdf5 = "calibration.h5"
summary = "summary.txt"
plot_data = "plot_data"
status = "fit_status.toml"
)";

TEST(StudyCalibration, IsTheConfigurationThatTheGeneratedFileGave) {
  const fs::path dir = fs::path(::testing::TempDir()) / "study_calibration" / "study";
  fs::remove_all(dir);
  fs::create_directories(dir);
  WriteTextFileAtomically((dir / "study.toml").string(), "programme = \"t\"\nncl = \"ncl\"\n");
  const std::string origin = (dir / "calibration/hypoplastic_clay/calibration.toml").string();
  const calibration::CalibrationConfig built =
      StudyCalibrationConfig(dir.string(), ModelKind::kHypoplasticClay, nullptr);
  calibration::testing::ExpectSameConfig(
      built, calibration::ReadCalibrationConfig(ConfigTable::ParseString(kStudyFile, origin)));
  // The file it leaves reads back as the same configuration.
  calibration::testing::ExpectSameConfig(
      built, calibration::ReadCalibrationConfig(
                 ConfigTable::ParseString(calibration::CalibrationConfigText(built), origin)));
  // Without an NCL case every detected state is taken.
  fs::remove(dir / "study.toml");
  EXPECT_TRUE(StudyCalibrationConfig(dir.string(), ModelKind::kHypoplasticClay, nullptr)
                  .datasets.front()
                  .study.ncl_references.empty());
}

TEST(StudyCalibration, ARateStudyIsFittedToItsQuasiStaticSetWithBothFitters) {
  const fs::path dir = fs::path(::testing::TempDir()) / "study_calibration" / "rate";
  fs::create_directories(dir);
  QuasiStaticSelection selection;
  selection.inertial_number = 1e-3;
  selection.youngs_modulus_mpa = 500;
  selection.cases = {"nc100_psi0_I0.001", "nc100_psi90_I0.001"};
  selection.drained_cases = {"tx100_ea0.01"};
  const std::string origin = (dir / "calibration/hypoplastic_sand/calibration.toml").string();
  const calibration::CalibrationConfig built =
      StudyCalibrationConfig(dir.string(), ModelKind::kHypoplasticSand, &selection);
  calibration::testing::ExpectSameConfig(
      built, calibration::ReadCalibrationConfig(ConfigTable::ParseString(kRateFile, origin)));
  const std::string text = calibration::CalibrationConfigText(built);
  calibration::testing::ExpectSameConfig(
      built, calibration::ReadCalibrationConfig(ConfigTable::ParseString(text, origin)));
  EXPECT_NE(text.find("study = \"../..\""), std::string::npos) << text;
}

// Issue 36 §2: the quasi-static selection of a study without rate cases,
// its states with I(d_max) below a bound, as a key of the file it leaves.
TEST(StudyCalibration, AQuasiStaticSelectionBoundsTheInertialNumber) {
  const fs::path dir = fs::path(::testing::TempDir()) / "study_calibration" / "bounded";
  fs::create_directories(dir);
  const std::string origin = (dir / "calibration/modified_cam_clay/calibration.toml").string();
  const calibration::CalibrationConfig built = StudyCalibrationConfig(
      dir.string(), ModelKind::kModifiedCamClay, nullptr, kQuasiStaticInertialNumber);
  ASSERT_EQ(built.datasets.size(), 1u);
  EXPECT_DOUBLE_EQ(built.datasets[0].study.max_inertial_number, 1e-3);
  const std::string text = calibration::CalibrationConfigText(built);
  EXPECT_NE(text.find("max_inertial_number = 0.001\n"), std::string::npos) << text;
  calibration::testing::ExpectSameConfig(
      built, calibration::ReadCalibrationConfig(ConfigTable::ParseString(text, origin)));
  // Without a bound the key is not written.
  EXPECT_EQ(calibration::CalibrationConfigText(
                StudyCalibrationConfig(dir.string(), ModelKind::kModifiedCamClay, nullptr))
                .find("max_inertial_number"),
            std::string::npos);
}

}  // namespace
}  // namespace granasym::analysis
#endif
