// The calibration of a study, built in code: the same configuration as the
// calibration file that `study calibrate` wrote and read back before, and a
// file that reads back as it.
#ifdef GRANASYM_ANALYSIS_HAS_CALIBRATION  // a build with the models (GRANASYM_BUILD_MODELS)
#include "analysis/study_calibration.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "calibration/model_parameters.h"
#include "common/config.h"
#include "common/text_file.h"
#include "constitutive/element_driver.h"
#include "tests/calibration/path_data.h"
#include "tests/calibration/same_config.h"
#include "tests/calibration/synthetic_data.h"

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
  // Not the study's default selection: its own folder (calibration_selections.h).
  const std::string origin =
      (dir / "calibration/quasi_static/modified_cam_clay/calibration.toml").string();
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

// A study with the paper's path cases (Fig. 9 cycles, Fig. 11 OC and NC
// isochoric, Fig. 12 drained) in replicate r1, a proportional case that is
// not a path, and an unfinished cycles case: the calibration takes the paths
// of the finished ones as whole-path datasets, and its file reads back.
TEST(StudyCalibration, TakesTheStudysCyclesIsochoricAndDrainedPaths) {
  const fs::path dir = fs::path(::testing::TempDir()) / "study_calibration_paths" / "study";
  fs::remove_all(dir);
  fs::create_directories(dir);
  WriteTextFileAtomically((dir / "study.toml").string(), "programme = \"t\"\nncl = \"ncl\"\n");
  std::string why;
  const auto model =
      calibration::MakeModel(ModelKind::kHypoplasticClay, calibration::testing::LondonClay(), &why);
  ASSERT_TRUE(model) << why;
  const auto write_case =
      [&](const std::string& name, const ModelState& start, const std::vector<LoadingStage>& stages,
          const std::vector<std::string>& names, const std::vector<std::string>& types,
          const std::vector<double>& psi, bool done) {
        const fs::path folder = dir / "cases" / "r1" / name;
        fs::create_directories(folder);
        calibration::testing::WriteModelRun(*model, (folder / "result.h5").string(), start, stages,
                                            names, types, psi);
        if (done) WriteTextFileAtomically((folder / "done.toml").string(), "key = \"k\"\n");
      };
  using calibration::testing::IsotropicTo;
  write_case("ncl_cycles", InitialStateFromOcr(*model, 200, 0, 1),
             {IsotropicTo(50, false), IsotropicTo(500, true)}, {"unload1", "reload1"},
             {"strain_path", "strain_path"}, {180.0, 0.0}, true);
  write_case("ncl_cycles_unfinished", InitialStateFromOcr(*model, 200, 0, 1),
             {IsotropicTo(50, false), IsotropicTo(500, true)}, {"unload1", "reload1"},
             {"strain_path", "strain_path"}, {180.0, 0.0}, false);
  for (double p : {2.0, 20.0, 100.0, 500.0}) {
    write_case(fmt::format("oc{}_psi90", p), InitialStateFromOcr(*model, p, 0, 1000.0 / p),
               {LoadingStage::Isochoric(1.0, 0.1)}, {"psi90"}, {"strain_path"}, {90.0}, true);
  }
  write_case("nc100_psi90", InitialStateFromOcr(*model, 100, 0, 1),
             {LoadingStage::Isochoric(1.0, 0.1)}, {"psi90"}, {"strain_path"}, {90.0}, true);
  write_case("nc200_triaxial", InitialStateFromOcr(*model, 200, 0, 1),
             {LoadingStage::ConstantRadialStress(1.0, 0.1)}, {"triaxial"}, {"triaxial"}, {}, true);
  write_case("nc100_psi30", InitialStateFromOcr(*model, 100, 0, 1),
             {LoadingStage::Proportional(30 * kDegree, 1.0, 0.05)}, {"psi30"}, {"strain_path"},
             {30.0}, true);
  std::vector<std::string> notes;
  const std::vector<calibration::DatasetConfig> paths = StudyPathDatasets(dir.string(), &notes);
  EXPECT_TRUE(notes.empty()) << notes.front();
  std::vector<std::string> cases;
  for (const calibration::DatasetConfig& d : paths) cases.push_back(d.path_case);
  // The cycles; of the OC isochoric paths from 20, 100 and 500 kPa (not
  // from 2 kPa, below kStudyPathMinStartKpa) the median; the NC isochoric
  // path; the drained path.
  EXPECT_EQ(cases, (std::vector<std::string>{"ncl_cycles", "oc100_psi90", "nc100_psi90",
                                             "nc200_triaxial"}));
  ASSERT_EQ(paths.size(), 4u);
  EXPECT_EQ(paths[0].path_read.kind, calibration::PathKind::kUnloadReload);
  EXPECT_EQ(paths[0].path_read.stages, (std::vector<std::string>{"unload1", "reload1"}));
  EXPECT_EQ(paths[3].path_read.kind, calibration::PathKind::kDrained);
  EXPECT_EQ(paths[3].path_read.control, calibration::PathControl::kDrained);
  const calibration::CalibrationConfig built =
      StudyCalibrationConfig(dir.string(), ModelKind::kHypoplasticClay, nullptr);
  ASSERT_EQ(built.datasets.size(), 5u);
  EXPECT_TRUE(built.datasets[1].is_path);
  EXPECT_EQ(built.datasets[1].path, (dir / "cases/r1/ncl_cycles/result.h5").string());
  const std::string text = calibration::CalibrationConfigText(built);
  EXPECT_NE(text.find("study_path = \"../..\"\ncase = \"ncl_cycles\""), std::string::npos) << text;
  calibration::testing::ExpectSameConfig(
      built, calibration::ReadCalibrationConfig(ConfigTable::ParseString(text, built.origin)));
}

}  // namespace
}  // namespace granasym::analysis
#endif
