// Admissibility checks and the diagnosis of structural misfit on data made to
// trigger them, the sand model's recovery from states along its own paths,
// and the [model] block of a fit running through `granasym model run`'s
// input reader (RunElementTestInput).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>

#include "calibration/calibration_report.h"
#include "calibration/ceres_fitter.h"
#include "calibration/starting_values.h"
#include "common/config.h"
#include "common/state_measures.h"
#include "constitutive/element_driver.h"
#include "constitutive/hypoplastic_sand.h"
#include "constitutive/model_config.h"
#include "synthetic_data.h"

namespace granasym::calibration {
namespace {

// A run of one Ceres fit on `datasets` (parameters chosen as RunCalibration does).
CalibrationRun FitRun(ModelKind kind, std::vector<StateDataset> datasets,
                      const std::vector<ParameterChoice>& choices = {}) {
  CalibrationRun run;
  run.config.model = kind;
  run.starting_values = EstimateStartingValues(datasets);
  ModelParameters parameters = ChooseParameters(kind, choices, run.starting_values, datasets);
  run.problem = std::make_unique<CalibrationProblem>(std::move(datasets), std::move(parameters),
                                                     PredictorOptions());
  run.fits.push_back(CeresFitter(CeresFitter::Options()).Fit(*run.problem));
  EXPECT_TRUE(run.fits[0].summary.success()) << run.fits[0].summary.Report();
  run.status.assign(run.problem->parameters().specs().size(), ParameterStatus::kFitted);
  run.findings = CheckAdmissibility(run, run.fits[0], &run.diagnosis);
  return run;
}

bool Has(const CalibrationRun& run, const std::string& code) {
  return std::any_of(run.findings.begin(), run.findings.end(),
                     [&](const Finding& f) { return f.code == code; });
}

std::string Lines(const CalibrationRun& run) {
  std::string s;
  for (const Finding& f : run.findings) s += f.Line() + "\n";
  return s;
}

StateDataset CamClayStates() {
  testing::SyntheticOptions options;
  options.psi_epsilons_deg = {0, 30, 60, 90};
  return testing::MakeSyntheticDataset(ModelKind::kModifiedCamClay, testing::CamClayTruth(),
                                       options);
}

AsymptoticStatePoint Point(StateKind kind, double psi_epsilon_deg, double p, double ln_v,
                           double psi_sigma_deg) {
  AsymptoticStatePoint point;
  point.kind = kind;
  point.psi_epsilon = psi_epsilon_deg * kDegree;
  point.mean_stress = p;
  point.void_ratio = std::expm1(ln_v);
  point.psi_sigma = psi_sigma_deg * kDegree;
  point.psi_sigma_uncertainty = 0.3 * kDegree;
  point.ln_volume_uncertainty = 0.002;
  point.source = "made";
  return point;
}

TEST(Admissibility, TheModelsOwnStatesRaiseNoWarning) {
  const CalibrationRun run = FitRun(ModelKind::kModifiedCamClay, {CamClayStates()});
  EXPECT_TRUE(run.findings.empty()) << Lines(run);
  EXPECT_FALSE(run.diagnosis.empty());
}

TEST(Admissibility, UnloadingSteeperThanTheNclWarnsKappaNotBelowLambda) {
  const std::vector<double> truth = testing::CamClayTruth();
  StateDataset unloading;
  unloading.name = "unloading";
  unloading.origin = "made";
  for (double p : {80.0, 40.0, 20.0}) {  // slope 2 λ* in ln(1+e)-ln p
    unloading.points.push_back(Point(StateKind::kUnloading, 180, p,
                                     truth[kNIntercept] - 2 * truth[kLambdaStar] * std::log(p), 0));
  }
  // κ* held valid so that the model exists; the data's own κ* ≥ λ* is the finding.
  ParameterChoice kappa;
  kappa.name = "kappa_star";
  kappa.free = false;
  kappa.has_value = true;
  kappa.value = truth[kKappaStar];
  const CalibrationRun run =
      FitRun(ModelKind::kModifiedCamClay, {CamClayStates(), unloading}, {kappa});
  EXPECT_TRUE(Has(run, "kappa_not_below_lambda")) << Lines(run);
}

TEST(Admissibility, StatesAboveTheNclWarnOcrBelowOneAndOutsideTheAsbs) {
  StateDataset made = CamClayStates();
  const std::vector<double> truth = testing::CamClayTruth();
  made.name = "made";
  // Compression states 0.05 above the NCL in ln(1+e): OCR ≈ exp(−0.05/λ*) ≈ 0.57.
  // Extension states likewise: beyond p/p_e* = 1.
  StateDataset above;
  above.name = "above";
  above.origin = "made";
  for (double p : {100.0, 300.0, 900.0}) {
    above.points.push_back(Point(StateKind::kCompression, 45, p,
                                 truth[kNIntercept] - truth[kLambdaStar] * std::log(p) + 0.05, 10));
    above.points.push_back(Point(StateKind::kExtension, 100, p,
                                 truth[kNIntercept] - truth[kLambdaStar] * std::log(p) + 0.05, 35));
    above.points.back().weight = 0;  // drawn, not fitted: still checked
    above.points[above.points.size() - 2].weight = 0;
  }
  const CalibrationRun run = FitRun(ModelKind::kModifiedCamClay, {made, above});
  EXPECT_TRUE(Has(run, "ocr_below_one")) << Lines(run);
  EXPECT_TRUE(Has(run, "asbs_outside")) << Lines(run);
  EXPECT_FALSE(Has(run, "structural_misfit")) << Lines(run);  // weight 0: not in the fit's misfit
}

TEST(Admissibility, ACslFarFromTheNclWarnsOcrMismatchAndStructuralMisfit) {
  // NCL and a CSL at OCR 5 (the DEM's kind of data): the hypoplastic clay
  // cannot put its CSL anywhere but OCR 2.
  const std::vector<double> truth = testing::LondonClay();
  StateDataset made;
  made.name = "made";
  made.origin = "made";
  for (double p : {50.0, 100.0, 200.0, 400.0, 800.0}) {
    made.points.push_back(
        Point(StateKind::kNcl, 0, p, truth[kNIntercept] - truth[kLambdaStar] * std::log(p), 0));
    made.points.push_back(Point(StateKind::kCsl, 90, p,
                                truth[kNIntercept] - truth[kLambdaStar] * std::log(5 * p), 24));
  }
  ParameterChoice r;
  r.name = "r";
  r.free = false;
  r.has_value = true;
  r.value = 0.4;
  ParameterChoice kappa = r;
  kappa.name = "kappa_star";
  kappa.value = 0.016;
  const CalibrationRun run = FitRun(ModelKind::kHypoplasticClay, {made}, {r, kappa});
  EXPECT_TRUE(Has(run, "csl_ocr_mismatch")) << Lines(run);
  EXPECT_TRUE(Has(run, "structural_misfit")) << Lines(run);
  const std::string text = WarningsText(run);
  EXPECT_NE(text.find("csl_ocr_mismatch: the data put the CSL at OCR = 5"), std::string::npos)
      << text;
}

// The sand's states by direct element tests: ψ_ε = 0 on e_i, 90° on e_c,
// else along proportional stretching from an isotropic state on e_i at a
// tenth of the lowest p, stopped at each p.
}  // namespace
StateDataset SandStates(const HypoplasticSand& sand, const std::vector<double>& pressures) {
  StateDataset d;
  d.name = "sand";
  d.origin = "synthetic";
  const double psi_c =
      std::atan(std::sqrt(2.0) / 3.0 * CriticalStateRatio(sand.critical_friction_angle()));
  for (double psi_deg : {0.0, 30.0, 60.0, 90.0}) {
    std::vector<ElementTestRecord> ends;
    if (psi_deg != 0 && psi_deg != 90) {
      // One stage per pressure, each stopping there (exactly, by root finding).
      std::vector<LoadingStage> stages;
      for (double p : pressures) {
        LoadingStage stage = LoadingStage::Proportional(psi_deg * kDegree, 1.0, 50.0);
        stage.stops.push_back({StopKind::kMeanStress, p});
        stages.push_back(stage);
      }
      const ElementTestResult result =
          ElementTest(sand, ElementTestOptions())
              .Run(InitialStateFromOcr(sand, pressures.front() / 10, 0.0, 1.0), stages);
      EXPECT_TRUE(result.summary.success()) << result.summary.Report();
      ends.resize(pressures.size());
      for (const ElementTestRecord& record : result.history) ends[record.stage] = record;
    }
    for (size_t k = 0; k < pressures.size(); ++k) {
      const double p = pressures[k];
      AsymptoticStatePoint point =
          Point(KindFromStretching(psi_deg * kDegree, 1e-9), psi_deg, p, 0, 0);
      if (psi_deg == 0) {
        point.void_ratio = sand.LimitVoidRatiosAt(p).loosest;
      } else if (psi_deg == 90) {
        point.void_ratio = sand.LimitVoidRatiosAt(p).critical;
        point.psi_sigma = psi_c;
      } else {
        EXPECT_NEAR(RecordStress(ends[k]).mean(), p, 1e-6 * p);
        point.void_ratio = ends[k].void_ratio;
        point.psi_sigma = RecordStress(ends[k]).psi();
      }
      d.points.push_back(point);
    }
  }
  return d;
}

namespace {
std::vector<double> DemLikeSand() { return {24.0, 1.7e5, 0.38, 0.46, 0.77, 0.83, 0.15, 1.0}; }

TEST(SandCalibration, StatesAlongItsOwnPathsRecoverTheParameters) {
  const std::vector<double> truth = DemLikeSand();
  std::string why;
  const auto model = MakeModel(ModelKind::kHypoplasticSand, truth, &why);
  ASSERT_TRUE(model) << why;
  const StateDataset data =
      SandStates(static_cast<const HypoplasticSand&>(*model), {50, 150, 450, 1000});
  // e_d0, α and β act on these states only through f_d off the axes: held.
  std::vector<ParameterChoice> held;
  for (int i : {kSandDensestVoidRatio, kSandPyknotropyExponent, kSandStiffnessExponent}) {
    ParameterChoice c;
    c.name = ModelParameters::Defaults(ModelKind::kHypoplasticSand).specs()[i].name;
    c.free = false;
    c.has_value = true;
    c.value = truth[i];
    held.push_back(c);
  }
  const CalibrationRun run = FitRun(ModelKind::kHypoplasticSand, {data}, held);
  const FitResult& fit = run.fits[0];
  EXPECT_NEAR(fit.values[kSandCriticalFrictionAngle], truth[kSandCriticalFrictionAngle], 0.05);
  EXPECT_NEAR(std::log(fit.values[kSandGranularHardness]), std::log(truth[kSandGranularHardness]),
              0.05);
  EXPECT_NEAR(fit.values[kSandExponent], truth[kSandExponent], 0.01);
  EXPECT_NEAR(fit.values[kSandCriticalVoidRatio], truth[kSandCriticalVoidRatio], 0.005);
  EXPECT_NEAR(fit.values[kSandLoosestVoidRatio], truth[kSandLoosestVoidRatio], 0.005);
  EXPECT_LT(fit.summary.final_cost, 1e-3) << fit.summary.Report();
  EXPECT_TRUE(run.findings.empty()) << Lines(run);

  // Its [model] block runs as an element test.
  const std::string toml = ModelToml(run, fit);
  const std::string out =
      (std::filesystem::temp_directory_path() / "granasym_sand_model_run.h5").string();
  const ElementTestResult result =
      RunElementTestInput(ConfigTable::ParseString(toml, "model.toml"), "model.toml", out, "");
  EXPECT_TRUE(result.summary.success()) << result.summary.Report() << "\n" << toml;
  // The plot data of the sand (no analytic ASBS) are written too.
  const std::string folder =
      (std::filesystem::temp_directory_path() / "granasym_sand_plot_data").string();
  WritePlotData(run, fit, folder);
  for (const char* name : {"states.csv", "model_curve.csv", "model_lines.dat"}) {
    EXPECT_TRUE(std::filesystem::exists(folder + "/" + name)) << name;
  }
}

TEST(ModelToml, TheClayModelsBlocksRunThroughTheElementTestReader) {
  for (ModelKind kind : {ModelKind::kHypoplasticClay, ModelKind::kModifiedCamClay}) {
    testing::SyntheticOptions options;
    options.psi_epsilons_deg = {0, 30, 60, 90, 110};
    const std::vector<double> truth =
        kind == ModelKind::kHypoplasticClay ? testing::LondonClay() : testing::CamClayTruth();
    const CalibrationRun run = FitRun(kind, {testing::MakeSyntheticDataset(kind, truth, options)});
    const std::string toml = ModelToml(run, run.fits[0]);
    EXPECT_NE(toml.find("[model]\nkind = \"" + std::string(ToString(kind)) + "\""),
              std::string::npos)
        << toml;
    const std::string out = (std::filesystem::temp_directory_path() /
                             ("granasym_model_run_" + std::string(ToString(kind)) + ".h5"))
                                .string();
    const ElementTestResult result =
        RunElementTestInput(ConfigTable::ParseString(toml, "model.toml"), "model.toml", out, "");
    EXPECT_TRUE(result.summary.success()) << result.summary.Report() << "\n" << toml;
  }
}

}  // namespace
}  // namespace granasym::calibration
namespace granasym::calibration {}
