// The overall status of a calibration (calibration/fit_status.h, issue 36
// §1) on data made for each of the five, through the library and through
// `granasym calibrate` (its exit status and status file); what the summary
// and parameters.csv say of standard errors that mean nothing; the
// comparison of Ceres and NLopt only when both converged.
#include "calibration/fit_status.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <set>
#include <sstream>

#include "calibration/calibration_config.h"
#include "calibration/calibration_report.h"
#include "calibration/csv_state_reader.h"
#include "common/config.h"
#include "common/error.h"
#include "common/text_file.h"
#include "synthetic_data.h"

namespace granasym::calibration {
namespace {
namespace fs = std::filesystem;

TEST(FitStatus, NamesPrecedenceAndExitStatuses) {
  const std::vector<std::pair<FitStatus, std::string>> spelled = {
      {FitStatus::kConverged, "converged"},
      {FitStatus::kConvergedInadmissible, "converged_inadmissible"},
      {FitStatus::kAtBound, "at_bound"},
      {FitStatus::kNoConvergence, "no_convergence"},
      {FitStatus::kFailed, "failed"}};
  for (const auto& [status, name] : spelled) {
    EXPECT_EQ(ToString(status), name);
    EXPECT_EQ(FromString<FitStatus>(name), status);
  }
  // failed > no_convergence > converged_inadmissible > at_bound > converged.
  const std::vector<FitStatus> order = {FitStatus::kConverged, FitStatus::kAtBound,
                                        FitStatus::kConvergedInadmissible,
                                        FitStatus::kNoConvergence, FitStatus::kFailed};
  for (size_t i = 0; i < order.size(); ++i) {
    for (size_t j = 0; j < order.size(); ++j) {
      EXPECT_EQ(Worst(order[i], order[j]), order[std::max(i, j)]) << i << " " << j;
    }
  }
  // 0 only for converged, a distinct status for each other, 3 as every failed fit.
  std::set<int> codes;
  for (FitStatus status : order) codes.insert(ExitStatus(status));
  EXPECT_EQ(codes.size(), order.size());
  EXPECT_EQ(ExitStatus(FitStatus::kConverged), 0);
  EXPECT_EQ(ExitStatus(FitStatus::kFailed), 3);
  EXPECT_EQ(codes.count(0), 1u);
  EXPECT_EQ(codes.count(2), 0u);  // bad input keeps its own
}

TEST(FitStatus, TheStatusFileHoldsExactlyStatusAndReason) {
  const fs::path dir = fs::temp_directory_path() / "granasym_tests" / "fit_status";
  fs::create_directories(dir);
  const std::string path = (dir / "status.toml").string();
  WriteTextFileAtomically(path, FitStatusToml({FitStatus::kAtBound, "kappa \"at\" a bound\nhere"}));
  const ConfigTable table = ConfigTable::ParseFile(path);
  EXPECT_EQ(table.Keys(), (std::vector<std::string>{"reason", "status"}));
  EXPECT_EQ(table.GetString("status"), "at_bound");
  const FitOutcome back = ReadFitStatusToml(path);
  EXPECT_EQ(back.status, FitStatus::kAtBound);
  EXPECT_EQ(back.reason, "kappa \"at\" a bound here");  // one line
  WriteTextFileAtomically(path, "status = \"fine\"\nreason = \"\"\n");
  EXPECT_THROW(ReadFitStatusToml(path), InputError);
  WriteTextFileAtomically(path, "status = \"converged\"\nreason = \"\"\nextra = 1\n");
  EXPECT_THROW(ReadFitStatusToml(path), InputError);
}

AsymptoticStatePoint Point(double psi_epsilon_deg, double p, double ln_v, double psi_sigma_deg) {
  AsymptoticStatePoint point;
  point.kind = KindFromStretching(psi_epsilon_deg * kDegree, 1e-9);
  point.psi_epsilon = psi_epsilon_deg * kDegree;
  point.mean_stress = p;
  point.void_ratio = std::expm1(ln_v);
  point.psi_sigma = psi_sigma_deg * kDegree;
  point.psi_sigma_uncertainty = 0.3 * kDegree;
  point.ln_volume_uncertainty = 0.002;
  point.source = "made";
  return point;
}

// Modified Cam clay's own states (testing::CamClayTruth) at ψ_ε = 0°, 30°,
// 60° and 90°: every parameter determined, the model admissible.
StateDataset CamClayStates() {
  testing::SyntheticOptions options;
  options.psi_epsilons_deg = {0, 30, 60, 90};
  return testing::MakeSyntheticDataset(ModelKind::kModifiedCamClay, testing::CamClayTruth(),
                                       options);
}

// The DEM's kind of data: an NCL and critical states at OCR 4 against it.
// Cam clay puts its CSL at OCR 2^(1 − κ*/λ*) ≤ 2: the fit drives κ* to its
// lower bound.
StateDataset CslFarFromTheNcl() {
  const std::vector<double> truth = testing::CamClayTruth();
  const double psi_c =
      std::atan(std::sqrt(2.0) / 3.0 * 6 * std::sin(28 * kDegree) / (3 - std::sin(28 * kDegree))) /
      kDegree;
  StateDataset d;
  d.name = "ncl_csl";
  d.origin = "made";
  for (double p : {50.0, 100.0, 200.0, 400.0, 800.0}) {
    d.points.push_back(Point(0, p, truth[kNIntercept] - truth[kLambdaStar] * std::log(p), 0));
    d.points.push_back(
        Point(90, p, truth[kNIntercept] - truth[kLambdaStar] * std::log(4 * p), psi_c));
  }
  return d;
}

// A scenario: its datasets as CSV files beside the calibration file that
// fits them (with `extra` keys: [parameters.*], [fitter]).
struct Scenario {
  std::string name;
  ModelKind model = ModelKind::kModifiedCamClay;
  std::vector<StateDataset> datasets;
  std::string extra;
};

std::string WriteScenario(const Scenario& s) {
  const fs::path dir = fs::temp_directory_path() / "granasym_tests" / "fit_status" / s.name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string toml = "[model]\nkind = \"" + std::string(ToString(s.model)) + "\"\n" + s.extra;
  for (size_t k = 0; k < s.datasets.size(); ++k) {
    const std::string csv = "data" + std::to_string(k) + ".csv";
    WriteStatesCsv(s.datasets[k], (dir / csv).string());
    toml += "\n[[dataset]]\nname = \"" + s.datasets[k].name + "\"\ncsv = \"" + csv + "\"\n";
  }
  WriteTextFileAtomically((dir / "calibration.toml").string(), toml);
  return (dir / "calibration.toml").string();
}

// Runs the scenario through the library and, in a build with the program,
// through `granasym calibrate`; expects `status` with `in_reason` in its reason.
CalibrationRun ExpectStatus(const Scenario& s, FitStatus status, const std::string& in_reason) {
  const std::string config = WriteScenario(s);
  CalibrationRun run = RunCalibration(ReadCalibrationConfigFile(config));
  const std::string summary = SummaryText(run);
  EXPECT_EQ(run.outcome.status, status) << s.name << ": " << run.outcome.reason << "\n" << summary;
  EXPECT_NE(run.outcome.reason.find(in_reason), std::string::npos) << run.outcome.reason;
  EXPECT_EQ(run.outcome.reason.find('\n'), std::string::npos);
  // The summary's first lines.
  std::istringstream lines(summary);
  std::string first, second, third;
  std::getline(lines, first);
  std::getline(lines, second);
  std::getline(lines, third);
  EXPECT_EQ(second, "status: " + std::string(ToString(status))) << summary;
  EXPECT_EQ(third, "reason: " + run.outcome.reason);
#ifdef GRANASYM_PROGRAM
  // The command line: the exit status of the status, and the status file.
  const fs::path dir = fs::path(config).parent_path();
  const std::string command = std::string("'") + GRANASYM_PROGRAM + "' calibrate '" + config +
                              "' --quiet > '" + (dir / "stdout.txt").string() + "' 2>&1";
  const int wait_status = std::system(command.c_str());
  if (!WIFEXITED(wait_status)) {
    ADD_FAILURE() << command << " did not exit";
    return run;
  }
  EXPECT_EQ(WEXITSTATUS(wait_status), ExitStatus(status))
      << s.name << ": " << ReadTextFile((dir / "stdout.txt").string());
  const FitOutcome written = ReadFitStatusToml((dir / "calibration_status.toml").string());
  EXPECT_EQ(written.status, status);
  EXPECT_EQ(written.reason, run.outcome.reason);
  EXPECT_NE(ReadTextFile((dir / "stdout.txt").string())
                .find("status: " + std::string(ToString(status)) + ": "),
            std::string::npos);
#endif
  return run;
}

TEST(FitStatus, TheModelsOwnStatesConverge) {
  const CalibrationRun run =
      ExpectStatus({"converged", ModelKind::kModifiedCamClay, {CamClayStates()}, ""},
                   FitStatus::kConverged, "converged after");
  // Every fitted parameter with a standard error and an interval (ν, which
  // states in two directions off the axes hardly determine, is fixed).
  std::istringstream csv(ParametersCsv(run, *run.kept_fit()));
  int fitted = 0;
  for (std::string line; std::getline(csv, line);) {
    // parameter,value,std_error,ci95_low,ci95_high,status,profile_low,profile_high,profile,units
    const size_t status = line.find(",fitted,");
    if (status == std::string::npos) continue;
    ++fitted;
    EXPECT_EQ(line.substr(0, status).find(",,"), std::string::npos) << line;
    // Determined by its profile likelihood too.
    EXPECT_NE(line.find(",determined,"), std::string::npos) << line;
  }
  EXPECT_GE(fitted, 4);
}

TEST(FitStatus, ACslTheModelCannotReachEndsAtABoundWithoutItsStandardError) {
  CalibrationRun run =
      ExpectStatus({"at_bound", ModelKind::kModifiedCamClay, {CslFarFromTheNcl()}, ""},
                   FitStatus::kAtBound, "kappa_star = 0.0001 at its lower bound 0.0001");
  // No standard error or interval at a bound.
  const std::string csv = ParametersCsv(run, *run.kept_fit());
  // Its profile stays below the threshold down to the bound: flat.
  EXPECT_NE(csv.find("\nkappa_star,0.0001,,,,at_bound,,,flat,1\n"), std::string::npos) << csv;
  EXPECT_NE(SummaryText(run).find("at bound"), std::string::npos) << SummaryText(run);
  // Nor in a near-null direction of the Jacobian (its standard error NaN).
  FitResult& fit = run.fits[run.kept];
  ASSERT_EQ(fit.free_indices.front(), kCriticalFrictionAngle);
  fit.standard_errors.front() = std::nan("");
  const std::string without = ParametersCsv(run, fit);
  const size_t phi = without.find("\nphi_c_deg,");
  ASSERT_NE(phi, std::string::npos);
  EXPECT_NE(without.find(",,,,fitted,", phi), std::string::npos) << without;
  const std::string summary = SummaryText(run);
  EXPECT_NE(summary.find("not determined"), std::string::npos) << summary;
  EXPECT_EQ(summary.find("nan"), std::string::npos) << summary;
}

TEST(FitStatus, AnInadmissibleModelsOwnStatesConvergeInadmissible) {
  // Hypoplastic clay with κ*/λ* = 0.3 at φ_c = 30°: its ASBS reaches p/p_e* ≈ 1.4
  // and its compression asymptotes lie at OCR < 1. The fit recovers it.
  testing::SyntheticOptions options;
  options.psi_epsilons_deg = {0, 30, 60, 90, 100};
  const StateDataset data = testing::MakeSyntheticDataset(ModelKind::kHypoplasticClay,
                                                          {30.0, 0.1, 0.03, 1.0, 0.4}, options);
  const CalibrationRun run =
      ExpectStatus({"inadmissible", ModelKind::kHypoplasticClay, {data}, ""},
                   FitStatus::kConvergedInadmissible, "the fitted model is inadmissible: ");
  bool flagged = false;
  for (const Finding& f : run.findings)
    flagged = flagged || (f.inadmissible && f.code == "asbs_outside");
  EXPECT_TRUE(flagged);
  EXPECT_NE(SummaryText(run).find("INADMISSIBLE asbs_outside"), std::string::npos);
}

TEST(FitStatus, AFitStoppedAfterOneIterationHasNotConverged) {
  ExpectStatus({"no_convergence",
                ModelKind::kModifiedCamClay,
                {CamClayStates()},
                "[parameters.phi_c_deg]\nvalue = 45.0\n[fitter]\nmax_iterations = 1\n"
                "fix_undetermined = false\n"},
               FitStatus::kNoConvergence, "before a convergence criterion was met");
}

TEST(FitStatus, UnloadingSteeperThanTheNclLeavesNoModelToFit) {
  // The unloading branch starts κ* above λ*: no model exists at the start.
  StateDataset data = CslFarFromTheNcl();
  const std::vector<double> truth = testing::CamClayTruth();
  for (double p : {80.0, 40.0, 20.0}) {
    data.points.push_back(
        Point(180, p, truth[kNIntercept] - 2 * truth[kLambdaStar] * std::log(p), 0));
  }
  ExpectStatus({"failed", ModelKind::kModifiedCamClay, {data}, ""}, FitStatus::kFailed,
               "the ceres fit failed: the model is undefined at the starting values");
}

TEST(FitStatus, CeresAndNloptAreComparedOnlyWhenBothConverged) {
  FitResult a, b;
  a.summary.fitter = "ceres";
  a.summary.termination = FitTermination::kConverged;
  b.summary.fitter = "nlopt:crs2+bobyqa";
  b.summary.termination = FitTermination::kNoConvergence;
  a.values = {1.0, 2.0};
  b.values = {1.5, 2.0};
  a.free_indices = {0, 1};
  a.standard_errors = {0.1, 0.1};
  a.at_bound = {false, false};
  std::string why;
  EXPECT_TRUE(std::isnan(FitAgreementInStandardErrors(a, b, &why)));
  EXPECT_NE(why.find("nlopt:crs2+bobyqa did not converge (no_convergence"), std::string::npos)
      << why;
  b.summary.termination = FitTermination::kConverged;
  EXPECT_DOUBLE_EQ(FitAgreementInStandardErrors(a, b, &why), 5.0);
  EXPECT_TRUE(why.empty());
  // A parameter at a bound has no standard error to compare in.
  a.at_bound = {true, false};
  EXPECT_DOUBLE_EQ(FitAgreementInStandardErrors(a, b, &why), 0.0);
  a.summary.termination = FitTermination::kFailure;
  EXPECT_TRUE(std::isnan(FitAgreementInStandardErrors(a, b, &why)));
  EXPECT_NE(why.find("ceres did not converge (failure"), std::string::npos) << why;
}

TEST(FitStatus, TheKeptFitIsTheConvergedOneOfLowestCost) {
  std::vector<FitResult> fits(3);
  fits[0].summary.termination = FitTermination::kNoConvergence;
  fits[0].summary.final_cost = 1.0;
  fits[1].summary.termination = FitTermination::kConverged;
  fits[1].summary.final_cost = 5.0;
  fits[2].summary.termination = FitTermination::kConverged;
  fits[2].summary.final_cost = 3.0;
  EXPECT_EQ(KeptFitIndex(fits), 2);
  fits[2].summary.termination = FitTermination::kFailure;
  EXPECT_EQ(KeptFitIndex(fits), 1);
  fits[1].summary.termination = FitTermination::kFailure;
  EXPECT_EQ(KeptFitIndex(fits), 0);
  EXPECT_EQ(KeptFitIndex({}), -1);
}

}  // namespace
}  // namespace granasym::calibration
