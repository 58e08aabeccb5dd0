// The calibration file: validation messages, and a whole run from CSV data to
// the HDF5 record, summary and plot data.
#include "calibration/calibration_config.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "calibration/calibration_report.h"
#include "calibration/csv_state_reader.h"
#include "calibration/model_parameters.h"
#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/key_table.h"
#include "common/text_file.h"
#include "synthetic_data.h"
#include "tests/calibration/same_config.h"
#include "tests/common/enum_spellings.h"

namespace granasym::calibration {
namespace {

const char* kConfig = R"(
[model]
kind = "hypoplastic_clay"

[parameters.r]
free = false
value = 0.4

[[dataset]]
name = "synthetic"
csv = "states.csv"
psi_sigma_uncertainty_deg = 0.3

[fitter]
method = "both"
[fitter.nlopt]
starts = 2
max_evaluations = 800
)";

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  if (at == std::string::npos)
    ADD_FAILURE() << "no '" << from << "'";
  else
    text.replace(at, from.size(), to);
  return text;
}

void ExpectRejected(const std::string& text, const std::string& expected) {
  try {
    ReadCalibrationConfig(ConfigTable::ParseString(text, "calib.toml"));
    FAIL() << "accepted: " << expected;
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("calib.toml"), std::string::npos) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  }
}

TEST(CalibrationConfig, ReadsAValidFile) {
  const CalibrationConfig c =
      ReadCalibrationConfig(ConfigTable::ParseString(kConfig, "/d/calib.toml"));
  EXPECT_EQ(c.model, ModelKind::kHypoplasticClay);
  EXPECT_EQ(c.method, FitMethod::kBoth);
  ASSERT_EQ(c.datasets.size(), 1u);
  EXPECT_EQ(c.datasets[0].path, "/d/states.csv");
  EXPECT_FALSE(c.datasets[0].is_dem);
  ASSERT_EQ(c.parameters.size(), 1u);
  EXPECT_FALSE(c.parameters[0].free);
  EXPECT_EQ(c.nlopt.starts, 2);
  EXPECT_EQ(c.hdf5_path, "/d/calib.h5");
  EXPECT_EQ(c.status_path, "/d/calib_status.toml");
}

// Every key the reader takes, none at its default.
const char* kEveryKey = R"(
[model]
kind = "modified_cam_clay"
asymptotes = "integrated"
[parameters.lambda_star]
free = true
value = 0.1
lower = 0.01
upper = 0.3
[parameters.poisson_ratio]
free = false
value = 0.25
[[dataset]]
name = "from a study"
study = "../study"
weight = 2.5
psi_sigma_uncertainty_deg = 0.7
ln_1_plus_e_uncertainty = 0.003
kinds = ["csl", "extension"]
statuses = ["detected", "drifting"]
exclude_flags = ["gas"]
ncl_references = ["ncl", "ncl_phi0"]
cases = ["nc100_psi90", "oc2_psi90"]
psi_epsilon_range_deg = [-10, 120.5]
triaxial_kind_tolerance_deg = 3.0
max_inertial_number = 0.002
[[dataset]]
name = "runs"
dem = ["a.h5", "sub/b.h5"]
weight = 0.0
ncl_min_p_kpa = 20
max_line_points = 7
asbs_ln_1_plus_e = [0.55, 0.5812345678901234]
unloading_weight = 0.25
[[dataset]]
name = "cycles"
dem_path = "runs/ncl_cycles.h5"
stages = ["unload1", "reload1"]
control = "strain"
path_kind = "unload_reload"
points = 55
ln_p_uncertainty = 0.03
weight = 2.0
[[dataset]]
name = "oc100"
study_path = "../study"
case = "oc100_psi90"
replicate = 2
stages = ["psi90"]
psi_sigma_uncertainty_deg = 0.7
ln_1_plus_e_uncertainty = 0.004
[[dataset]]
name = "table"
csv = "/abs/states.csv"
kind = "csl"
ignore_columns = "q_kpa,t_s"
psi_sigma_uncertainty_deg = 1e-3
[fitter]
method = "nlopt"
fix_undetermined = false
max_iterations = 77
scale_by_residual_variance = false
profiles = false
profile_points_per_side = 5
pareto = false
pareto_points = 13
[fitter.nlopt]
algorithm = "isres"
starts = 5
max_evaluations = 900
seed = 42
polish = "ceres"
[output]
hdf5 = "out/c.h5"
summary = "out/c.txt"
plot_data = "plots"
status = "out/c_status.toml"
)";

TEST(CalibrationConfig, ItsTextReadsBackAsTheSameConfiguration) {
  const CalibrationConfig c =
      ReadCalibrationConfig(ConfigTable::ParseString(kEveryKey, "/d/e/calib.toml"));
  const std::string text = CalibrationConfigText(c, "# a header\n");
  EXPECT_EQ(text.rfind("# a header\n", 0), 0u) << text;
  const CalibrationConfig again = ReadCalibrationConfig(ConfigTable::ParseString(text, c.origin));
  testing::ExpectSameConfig(c, again);
  // Paths stay relative to the file's folder, so the folder can move.
  EXPECT_NE(text.find("study = \"../study\""), std::string::npos) << text;
  EXPECT_NE(text.find("dem = [\"a.h5\", \"sub/b.h5\"]"), std::string::npos) << text;
  EXPECT_NE(text.find("dem_path = \"runs/ncl_cycles.h5\""), std::string::npos) << text;
  EXPECT_NE(text.find("study_path = \"../study\"\ncase = \"oc100_psi90\"\nreplicate = 2"),
            std::string::npos)
      << text;
  // The path datasets as read: a study case's result.h5.
  ASSERT_GE(c.datasets.size(), 4u);
  const DatasetConfig& cycles = c.datasets[2];
  const DatasetConfig& oc = c.datasets[3];
  EXPECT_TRUE(cycles.is_path && oc.is_path);
  EXPECT_EQ(cycles.path, "/d/e/runs/ncl_cycles.h5");
  EXPECT_EQ(cycles.path_read.points, 55);
  EXPECT_EQ(cycles.path_read.control, PathControl::kStrain);
  EXPECT_EQ(cycles.path_read.kind, PathKind::kUnloadReload);
  EXPECT_EQ(cycles.path_read.weight, 2.0);
  EXPECT_EQ(cycles.path_read.psi_sigma_uncertainty_deg, 1.0);  // the paths' default
  EXPECT_EQ(oc.path, "/d/study/cases/r2/oc100_psi90/result.h5");
  EXPECT_EQ(oc.path_read.control, PathControl::kAuto);
  EXPECT_EQ(oc.path_read.points, 40);
  EXPECT_EQ(c.datasets[1].dem.unloading_weight, 0.25);
  EXPECT_EQ(CalibrationConfigText(again, "# a header\n"), text);
  // And a configuration at every default.
  const CalibrationConfig plain =
      ReadCalibrationConfig(ConfigTable::ParseString(kConfig, "/d/calib.toml"));
  testing::ExpectSameConfig(plain, ReadCalibrationConfig(ConfigTable::ParseString(
                                       CalibrationConfigText(plain), plain.origin)));
}

TEST(CalibrationConfig, RejectsBadFilesNamingTheKey) {
  ExpectRejected(Replace(kConfig, "kind = \"hypoplastic_clay\"", "kind = \"sand\""), "kind");
  ExpectRejected(Replace(kConfig, "method = \"both\"", "method = \"simplex\""), "method");
  ExpectRejected(Replace(kConfig, "free = false\nvalue = 0.4", "free = false"), "value");
  ExpectRejected(Replace(kConfig, "value = 0.4", "value = 0.4\nlower = 2.0\nfree_ = 1"), "free_");
  ExpectRejected(Replace(kConfig, "[parameters.r]", "[parameters.lambda]"), "lambda");
  ExpectRejected(Replace(kConfig, "csv = \"states.csv\"", "dem = \"a.h5\"\ncsv = \"b.csv\""),
                 "exactly one");
  ExpectRejected(Replace(kConfig, "starts = 2", "starts = 0"), "starts");
  ExpectRejected(
      Replace(kConfig, "psi_sigma_uncertainty_deg = 0.3", "psi_sigma_uncertainty_deg = -1"),
      "psi_sigma_uncertainty_deg");
  ExpectRejected("[model]\nkind = \"hypoplastic_clay\"\n", "dataset");
  ExpectRejected(Replace(kConfig, "method = \"both\"", "method = \"both\"\npareto_points = 12"),
                 "pareto_points = 12 must be odd");
  ExpectRejected(Replace(kConfig, "method = \"both\"", "method = \"both\"\npareto_points = 3"),
                 "pareto_points");
  ExpectRejected(
      Replace(kConfig, "method = \"both\"", "method = \"both\"\nprofile_points_per_side = 1"),
      "profile_points_per_side");
}

// Calibration fits the clay models only: the sand model is a valid model kind
// elsewhere but gets the normal "kind" error here, listing the allowed kinds.
TEST(CalibrationConfig, ReadsTheSandModelWithItsOwnParameterNames) {
  const std::string sand =
      Replace(kConfig, "kind = \"hypoplastic_clay\"", "kind = \"hypoplastic_sand\"");
  // r belongs to the clay: an unknown key for the sand.
  ExpectRejected(sand, "parameters.r");
  const CalibrationConfig c = ReadCalibrationConfig(
      ConfigTable::ParseString(Replace(sand, "[parameters.r]\nfree = false\nvalue = 0.4",
                                       "[parameters.beta]\nfree = false\nvalue = 1.2"),
                               "/d/calib.toml"));
  EXPECT_EQ(c.model, ModelKind::kHypoplasticSand);
  ASSERT_EQ(c.parameters.size(), 1u);
  EXPECT_EQ(c.parameters[0].name, "beta");
  EXPECT_DOUBLE_EQ(c.parameters[0].value, 1.2);
}

// Calibration files and the HDF5 record use these spellings.
TEST(CalibrationConfig, NamesAreSpelledAsInFilesAndResults) {
  ExpectSpellings<FitMethod>(
      {{FitMethod::kCeres, "ceres"}, {FitMethod::kNlopt, "nlopt"}, {FitMethod::kBoth, "both"}});
  ExpectSpellings<AsymptoteMethod>(
      {{AsymptoteMethod::kAnalytic, "analytic"}, {AsymptoteMethod::kIntegrated, "integrated"}});
  ExpectSpellings<GlobalAlgorithm>({{GlobalAlgorithm::kCrs2, "crs2"},
                                    {GlobalAlgorithm::kIsres, "isres"},
                                    {GlobalAlgorithm::kDirectL, "direct_l"},
                                    {GlobalAlgorithm::kMlsl, "mlsl"}});
  ExpectSpellings<LocalPolish>({{LocalPolish::kNone, "none"},
                                {LocalPolish::kBobyqa, "bobyqa"},
                                {LocalPolish::kCeres, "ceres"}});
  ExpectSpellings<FitTermination>({{FitTermination::kConverged, "converged"},
                                   {FitTermination::kNoConvergence, "no_convergence"},
                                   {FitTermination::kFailure, "failure"}});
}

TEST(CalibrationConfig, ReadsEveryNameAndListsTheAllowedOnes) {
  const std::string nlopt =
      Replace(kConfig, "starts = 2", "starts = 2\nalgorithm = \"direct_l\"\npolish = \"none\"");
  const std::string text =
      Replace(Replace(Replace(nlopt, "kind = \"hypoplastic_clay\"",
                              "kind = \"modified_cam_clay\"\nasymptotes = \"integrated\""),
                      "method = \"both\"", "method = \"nlopt\""),
              "csv = \"states.csv\"", "csv = \"states.csv\"\nkind = \"asbs\"");
  const CalibrationConfig c = ReadCalibrationConfig(ConfigTable::ParseString(
      Replace(text, "[parameters.r]", "[parameters.poisson_ratio]"), "/d/calib.toml"));
  EXPECT_EQ(c.model, ModelKind::kModifiedCamClay);
  EXPECT_EQ(c.predictor.method, AsymptoteMethod::kIntegrated);
  EXPECT_EQ(c.method, FitMethod::kNlopt);
  EXPECT_EQ(c.nlopt.algorithm, GlobalAlgorithm::kDirectL);
  EXPECT_EQ(c.nlopt.polish, LocalPolish::kNone);
  EXPECT_EQ(c.datasets[0].csv.kind, "asbs");

  ExpectRejected(Replace(kConfig, "method = \"both\"", "method = \"simplex\""),
                 "key 'fitter.method' = 'simplex' is not valid: expected ceres, nlopt or both");
  ExpectRejected(Replace(kConfig, "starts = 2", "starts = 2\npolish = \"lbfgs\""),
                 "expected none, bobyqa or ceres");
  ExpectRejected(Replace(kConfig, "csv = \"states.csv\"", "csv = \"states.csv\"\nkind = \"nel\""),
                 "key 'dataset[0].kind' = 'nel' is not valid: expected auto, ncl, csl, "
                 "compression, extension, asbs or unloading");
  ExpectRejected(Replace(kConfig, "kind = \"hypoplastic_clay\"", "kind = \"mohr_coulomb\""),
                 "expected hypoplastic_clay, modified_cam_clay or hypoplastic_sand");
}

TEST(CalibrationConfig, ReadsAndChecksAsbsValuesOfADemDataset) {
  const std::string dem = Replace(kConfig, "csv = \"states.csv\"", "dem = \"run.h5\"");
  const CalibrationConfig c = ReadCalibrationConfig(ConfigTable::ParseString(
      Replace(dem, "dem = \"run.h5\"", "dem = \"run.h5\"\nasbs_ln_1_plus_e = [0.55, 0.58]"),
      "/d/calib.toml"));
  ASSERT_EQ(c.datasets.size(), 1u);
  EXPECT_TRUE(c.datasets[0].is_dem);
  EXPECT_EQ(c.datasets[0].dem.asbs_ln_1_plus_e, (std::vector<double>{0.55, 0.58}));
  EXPECT_TRUE(ReadCalibrationConfig(ConfigTable::ParseString(dem, "/d/calib.toml"))
                  .datasets[0]
                  .dem.asbs_ln_1_plus_e.empty());
  for (const char* bad : {"[0.55, nan]", "[0.55, 0.0]", "[-0.1]", "[]", "0.55"}) {
    ExpectRejected(Replace(dem, "dem = \"run.h5\"",
                           std::string("dem = \"run.h5\"\nasbs_ln_1_plus_e = ") + bad),
                   "asbs_ln_1_plus_e");
  }
}

TEST(CalibrationConfig, RunsAWholeCalibrationAndWritesItsRecord) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "granasym_calibration_run";
  std::filesystem::create_directories(dir);
  const std::vector<double> truth = testing::LondonClay();
  WriteStatesCsv(testing::MakeSyntheticDataset(ModelKind::kHypoplasticClay, truth, {}),
                 (dir / "states.csv").string());
  {
    std::ofstream out(dir / "calib.toml");
    out << kConfig;
  }
  const CalibrationConfig config = ReadCalibrationConfigFile((dir / "calib.toml").string());
  const CalibrationRun run = RunCalibration(config);
  ASSERT_EQ(run.fits.size(), 2u);
  EXPECT_TRUE(run.starting_values.lambda_star.from_data);
  EXPECT_LT(run.agreement_in_standard_errors, 0.1);
  for (const FitResult& fit : run.fits) {
    EXPECT_TRUE(fit.summary.success()) << fit.summary.Report();
    EXPECT_DOUBLE_EQ(fit.values[kShearParameter], 0.4);  // fixed
    EXPECT_EQ(fit.free_indices.size(), 4u);
    EXPECT_NEAR(fit.values[kLambdaStar], truth[kLambdaStar], 0.01);
  }
  WriteCalibrationHdf5(run, config.hdf5_path);
  WritePlotData(run, run.fits[0], config.plot_data_dir);
  const std::string summary = SummaryText(run);
  EXPECT_NE(summary.find("95 % interval"), std::string::npos);
  EXPECT_NE(summary.find("UMAT"), std::string::npos);
  EXPECT_NE(summary.find("ceres vs nlopt"), std::string::npos);
  // Full rank: the correlations of (JᵀJ)⁻¹, not null directions.
  EXPECT_NE(summary.find("correlation matrix (free parameters; (J^T J)^-1 normalised)"),
            std::string::npos)
      << summary;
  EXPECT_EQ(summary.find("correlations not reported"), std::string::npos) << summary;

  const Hdf5File file = Hdf5File::OpenRead(config.hdf5_path);
  const std::vector<double> values = file.ReadDoubles("/fits/ceres/values");
  ASSERT_EQ(values.size(), 5u);
  EXPECT_DOUBLE_EQ(values[kLambdaStar], run.fits[0].values[kLambdaStar]);
  EXPECT_EQ(file.ReadDoubles("/fits/ceres/standard_errors").size(), 4u);
  EXPECT_EQ(file.ReadStringAttribute("/fits/ceres/export_umat", "order"),
            "phi_c_deg,lambda_star,kappa_star,N,r");
  EXPECT_TRUE(file.Exists("/fits/nlopt_crs2_bobyqa/history/cost"));
  EXPECT_EQ(file.ReadDoubles("/data/p_kpa").size(), run.problem->datasets()[0].points.size());
  EXPECT_TRUE(std::filesystem::exists(config.plot_data_dir + "/states.csv"));
  EXPECT_TRUE(std::filesystem::exists(config.plot_data_dir + "/model_curve.csv"));
  EXPECT_TRUE(std::filesystem::exists(config.plot_data_dir + "/model_lines.dat"));
  // The profiles of the four free parameters and the front (on by default).
  ASSERT_EQ(run.profiles.profiles.size(), 4u);
  EXPECT_NE(summary.find("profile likelihood: 4 parameters"), std::string::npos) << summary;
  EXPECT_NE(summary.find("pareto front: ncl_compression"), std::string::npos) << summary;
  EXPECT_TRUE(std::filesystem::exists(config.plot_data_dir + "/profiles.csv"));
  EXPECT_TRUE(std::filesystem::exists(config.plot_data_dir + "/pareto.csv"));
  const std::string parameters = ParametersCsv(run, run.fits[0]);
  EXPECT_EQ(parameters.rfind("parameter,value,std_error,ci95_low,ci95_high,status,profile_low,"
                             "profile_high,profile,units\n",
                             0),
            0u)
      << parameters;
  EXPECT_NE(parameters.find(",determined,"), std::string::npos) << parameters;
  std::filesystem::remove_all(dir);
}

// Only the NCL and the CSL (what a rate study's quasi-static set holds when
// its extension paths liquefy): r acts on neither, so fix_undetermined fixes
// it before the fit and says why; without fix_undetermined the run refuses.
TEST(CalibrationConfig, FixesWhatTheDataCannotIdentifyBeforeTheFit) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "granasym_calibration_axes";
  std::filesystem::create_directories(dir);
  const std::vector<double> truth = testing::LondonClay();
  testing::SyntheticOptions data;
  data.psi_epsilons_deg = {0, 90};
  WriteStatesCsv(testing::MakeSyntheticDataset(ModelKind::kHypoplasticClay, truth, data),
                 (dir / "states.csv").string());
  const std::string text = Replace(Replace(kConfig, "free = false\nvalue = 0.4", "value = 0.4"),
                                   "method = \"both\"", "method = \"ceres\"");
  std::ofstream(dir / "calib.toml") << text;
  const CalibrationRun run =
      RunCalibration(ReadCalibrationConfigFile((dir / "calib.toml").string()));
  ASSERT_EQ(run.fits.size(), 1u);
  EXPECT_TRUE(run.fits[0].summary.success()) << run.fits[0].summary.Report();
  EXPECT_EQ(run.status[kShearParameter], ParameterStatus::kUndetermined);
  EXPECT_DOUBLE_EQ(run.fits[0].values[kShearParameter], 0.4);
  ASSERT_FALSE(run.undetermined.empty());
  EXPECT_NE(run.undetermined.front().find("r fixed at its start value 0.4: these data cannot "
                                          "identify it (r needs non-isotropic states in two"),
            std::string::npos)
      << run.undetermined.front();
  EXPECT_NEAR(run.fits[0].values[kCriticalFrictionAngle], truth[kCriticalFrictionAngle], 0.1);
  std::ofstream(dir / "calib.toml")
      << Replace(text, "method = \"ceres\"", "method = \"ceres\"\nfix_undetermined = false");
  try {
    RunCalibration(ReadCalibrationConfigFile((dir / "calib.toml").string()));
    ADD_FAILURE() << "fitted an r that the data cannot identify";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("parameter r cannot be identified"), std::string::npos)
        << error.what();
  }
  std::filesystem::remove_all(dir);
}

TEST(CalibrationConfig, RefusesTooFewPointsForTheFreeParameters) {
  CsvReadOptions options;
  const StateDataset tiny = ParseStatesCsv("p_kpa,e,psi_sigma_deg,psi_epsilon_deg\n100,0.8,0,0\n",
                                           "tiny.csv", "tiny", options);
  try {
    CalibrationProblem problem({tiny}, ModelParameters::Defaults(ModelKind::kHypoplasticClay),
                               PredictorOptions());
    FAIL() << "accepted 2 residuals for 5 parameters";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("too few data"), std::string::npos) << error.what();
  }
  try {
    CalibrationProblem problem({}, ModelParameters::Defaults(ModelKind::kHypoplasticClay),
                               PredictorOptions());
    FAIL() << "accepted no datasets";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("no datasets"), std::string::npos);
  }
}

// A fit that did not converge stops where its solver gave up: its values are
// not an optimum, and the summary must not report a "difference of 0
// standard errors" against it (the rate study's clay calibration did, with
// Ceres's Jacobian failing). Issue 36 §1: only when both converged.
TEST(CalibrationConfig, FitsAreComparedOnlyWhenBothConvergedWithStandardErrors) {
  FitResult ceres;
  ceres.summary.fitter = "ceres";
  ceres.summary.termination = FitTermination::kConverged;
  ceres.values = {1.0, 2.0, 3.0};
  ceres.free_indices = {0, 2};
  ceres.standard_errors = {0.5, 0.1};
  FitResult nlopt = ceres;
  nlopt.summary.fitter = "nlopt:crs2+bobyqa";
  nlopt.values = {1.25, 7.0, 3.05};  // index 1 is fixed: not compared
  std::string why_not;
  EXPECT_DOUBLE_EQ(FitAgreementInStandardErrors(ceres, nlopt, &why_not), 0.5);
  EXPECT_EQ(why_not, "");

  FitResult failed = ceres;
  failed.summary.termination = FitTermination::kFailure;
  failed.summary.message = "Residual and Jacobian evaluation failed.";
  EXPECT_TRUE(std::isnan(FitAgreementInStandardErrors(failed, nlopt, &why_not)));
  EXPECT_EQ(why_not,
            "ceres did not converge (failure: Residual and Jacobian evaluation failed.), so "
            "there is no pair of optima to compare");
  nlopt.summary.termination = FitTermination::kNoConvergence;
  nlopt.summary.message = "BOBYQA reached polish_max_evaluations";
  EXPECT_TRUE(std::isnan(FitAgreementInStandardErrors(ceres, nlopt, &why_not)));
  EXPECT_NE(why_not.find("nlopt:crs2+bobyqa did not converge (no_convergence: BOBYQA"),
            std::string::npos)
      << why_not;
  EXPECT_TRUE(std::isnan(FitAgreementInStandardErrors(failed, nlopt, &why_not)));
  EXPECT_NE(why_not.find("ceres did not converge (failure: Residual and Jacobian evaluation "
                         "failed.) and nlopt:crs2+bobyqa did not converge"),
            std::string::npos)
      << why_not;

  nlopt.summary.termination = FitTermination::kConverged;
  ceres.standard_errors = {std::nan(""), 0.0};
  EXPECT_TRUE(std::isnan(FitAgreementInStandardErrors(ceres, nlopt, &why_not)));
  EXPECT_EQ(why_not,
            "ceres reports no standard error of any free parameter (each is undetermined or at a "
            "bound)");
}

// Every example of calibration/examples/ reads (one per model), and
// docs/guide/calibration-file.md lists every key that the writer writes for a file
// with every kind of dataset and every key the examples use.
TEST(CalibrationConfig, ExamplesReadAndTheDocumentationListsEveryKey) {
  const std::string root = GRANASYM_SOURCE_DIR;
  const std::string docs = ReadTextFile(root + "/docs/guide/calibration-file.md");
  std::set<std::string> keys;
  const auto collect = [&keys](const std::string& text) {
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
      const size_t eq = line.find(" = ");
      if (line.empty() || line[0] == '#' || eq == std::string::npos) continue;
      keys.insert(line.substr(0, eq));
    }
  };
  std::set<ModelKind> models;
  for (const char* name : {"hypoplastic_clay", "modified_cam_clay", "hypoplastic_sand"}) {
    const std::string file = root + "/calibration/examples/" + name + ".toml";
    SCOPED_TRACE(file);
    const CalibrationConfig c = ReadCalibrationConfigFile(file);
    models.insert(c.model);
    EXPECT_EQ(ToString(c.model), std::string(name));
    bool has_path = false;
    for (const DatasetConfig& d : c.datasets) has_path |= d.is_path;
    EXPECT_TRUE(has_path) << "each example fits whole paths too";
    collect(ReadTextFile(file));
    collect(CalibrationConfigText(c));
  }
  EXPECT_EQ(models.size(), 3u);
  collect(CalibrationConfigText(
      ReadCalibrationConfig(ConfigTable::ParseString(kEveryKey, "/d/e/calib.toml"))));
  EXPECT_GT(keys.size(), 40u);
  for (const std::string& key : keys) {
    EXPECT_NE(docs.find("\n" + key + " = "), std::string::npos)
        << "docs/guide/calibration-file.md does not list the key '" << key << "'";
  }
}

}  // namespace
}  // namespace granasym::calibration

namespace granasym::calibration {
namespace {

// The key table against the parser: every key of the table is read by some
// file (kEveryKey, and every model's parameter tables), every key a file may
// hold is in it (the parser's reads consult it), made-up keys are refused.
TEST(CalibrationKeys, EveryKeyOfTheTableIsReadAndMadeUpKeysAreRefused) {
  CalibrationKeys().ResetConsulted();
  ReadCalibrationConfig(ConfigTable::ParseString(kEveryKey, "/d/e/calib.toml"));
  for (ModelKind kind : EnumValues<ModelKind>()) {
    std::string text = fmt::format("[model]\nkind = \"{}\"\n", ToString(kind));
    const ModelParameters defaults = ModelParameters::Defaults(kind);
    for (const ParameterSpec& spec : defaults.specs()) {
      text += fmt::format(
          "[parameters.{}]\nfree = true\nvalue = {:.17g}\nlower = {:.17g}\nupper = {:.17g}\n",
          spec.name, spec.value, spec.lower, spec.upper);
    }
    text += "[[dataset]]\ncsv = \"states.csv\"\n";
    const CalibrationConfig config =
        ReadCalibrationConfig(ConfigTable::ParseString(text, "k.toml"));
    EXPECT_EQ(config.parameters.size(), defaults.specs().size());
  }
  const std::vector<std::string> unread = CalibrationKeys().Unconsulted();
  EXPECT_TRUE(unread.empty()) << "never read: " << unread.front();
  ExpectRejected(std::string(kConfig) + "[output]\nhdf6 = \"x.h5\"\n",
                 "key 'output.hdf6' is not a known key (valid keys here: hdf5, plot_data, "
                 "status, summary)");
  const std::string markdown = CalibrationKeys().Render(KeyFormat::kMarkdown);
  EXPECT_NE(markdown.find("## [parameters.lambda_star]"), std::string::npos) << markdown;
}

}  // namespace
}  // namespace granasym::calibration
