// Synthetic recovery with Ceres and NLopt: data from each model with known
// parameters plus noise; the fits recover the parameters within their 95 %
// intervals and agree with each other.
#include "calibration/ceres_fitter.h"

#include <glog/logging.h>
#include <gtest/gtest.h>

#include <cmath>

#include "calibration/calibration_problem.h"
#include "calibration/calibration_report.h"
#include "calibration/nlopt_fitter.h"
#include "calibration/starting_values.h"
#include "common/error.h"
#include "synthetic_data.h"

namespace granasym::calibration {
namespace {

ModelParameters StartAwayFrom(ModelKind kind, const std::vector<double>& truth) {
  ModelParameters parameters = ModelParameters::Defaults(kind);
  const double factors[] = {1.15, 0.8, 1.4, 0.95, 1.3};
  for (int i = 0; i < kNumClayParameters; ++i)
    parameters.mutable_specs()[i].value = truth[i] * factors[i];
  return parameters;
}

void ExpectRecovered(const FitResult& fit, const std::vector<double>& truth) {
  ASSERT_TRUE(fit.summary.success()) << fit.summary.Report();
  ASSERT_EQ(fit.standard_errors.size(), fit.free_indices.size());
  for (size_t k = 0; k < fit.free_indices.size(); ++k) {
    const int i = fit.free_indices[k];
    EXPECT_TRUE(std::isfinite(fit.standard_errors[k])) << i;
    EXPECT_GT(fit.standard_errors[k], 0.0) << i;
    EXPECT_LE(fit.lower_95[k], truth[i])
        << "parameter " << i << ": " << fit.values[i] << " ± " << fit.standard_errors[k];
    EXPECT_GE(fit.upper_95[k], truth[i])
        << "parameter " << i << ": " << fit.values[i] << " ± " << fit.standard_errors[k];
    // The interval is informative: narrower than 30 % of the value, except for
    // r or ν, which act on the asymptotes only weakly (through the shear
    // stiffness in the direction of stretching).
    const double width = i == kShearParameter ? 2.0 : 0.3;
    EXPECT_LT(fit.upper_95[k] - fit.lower_95[k], width * std::abs(truth[i])) << i;
  }
}

TEST(CeresFitter, DefaultOptionsAreValid) {
  std::string why;
  EXPECT_TRUE(CeresFitter::Options().IsValid(&why)) << why;
  EXPECT_TRUE(UncertaintyOptions().IsValid(&why)) << why;
  CeresFitter::Options bad;
  bad.relative_step = 0.5;
  EXPECT_FALSE(bad.IsValid(&why));
  EXPECT_NE(why.find("relative_step"), std::string::npos);
}

TEST(CeresFitter, RecoversHypoplasticParametersWithinTheirIntervals) {
  const std::vector<double> truth = testing::LondonClay();
  CalibrationProblem problem(
      {testing::MakeSyntheticDataset(ModelKind::kHypoplasticClay, truth, {})},
      StartAwayFrom(ModelKind::kHypoplasticClay, truth), PredictorOptions());
  const FitResult fit = CeresFitter(CeresFitter::Options()).Fit(problem);
  EXPECT_EQ(fit.summary.termination, FitTermination::kConverged) << fit.summary.Report();
  ExpectRecovered(fit, truth);
  EXPECT_LT(fit.summary.final_cost, fit.summary.initial_cost);
  EXPECT_FALSE(fit.history.empty());
  // Noise at the stated uncertainties: s² near 1.
  EXPECT_GT(fit.residual_variance, 0.5);
  EXPECT_LT(fit.residual_variance, 1.6);
  EXPECT_EQ(fit.correlation.rows(), 5);
  EXPECT_NEAR(fit.correlation(0, 0), 1.0, 1e-12);
}

TEST(CeresFitter, RecoversCamClayParametersWithinTheirIntervals) {
  const std::vector<double> truth = testing::CamClayTruth();
  testing::SyntheticOptions options;
  options.psi_epsilons_deg = {0, 30, 60, 90, 100, -30, -60};
  CalibrationProblem problem(
      {testing::MakeSyntheticDataset(ModelKind::kModifiedCamClay, truth, options)},
      StartAwayFrom(ModelKind::kModifiedCamClay, truth), PredictorOptions());
  const FitResult fit = CeresFitter(CeresFitter::Options()).Fit(problem);
  ExpectRecovered(fit, truth);
}

// Ceres's own log lines ("Terminating: Residual and Jacobian evaluation
// failed.", and glog's warning that it was not initialised) stay off stderr
// once a fit ran: the fit reports every solve's termination itself.
TEST(CeresFitter, CeresLogLinesStayOffStderr) {
  const std::vector<double> truth = testing::CamClayTruth();
  CalibrationProblem problem(
      {testing::MakeSyntheticDataset(ModelKind::kModifiedCamClay, truth, {})},
      StartAwayFrom(ModelKind::kModifiedCamClay, truth), PredictorOptions());
  ::testing::internal::CaptureStderr();
  CeresFitter(CeresFitter::Options()).Fit(problem);
  LOG(ERROR) << "Terminating: a line as Ceres writes it";
  LOG(WARNING) << "a warning as Ceres writes it";
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(err.find("Terminating"), std::string::npos) << err;
  EXPECT_EQ(err.find("InitGoogleLogging"), std::string::npos) << err;
  EXPECT_EQ(err.find("a warning"), std::string::npos) << err;
}

TEST(NloptFitter, DefaultOptionsAreValid) {
  std::string why;
  EXPECT_TRUE(NloptFitter::Options().IsValid(&why)) << why;
  NloptFitter::Options bad;
  bad.starts = 0;
  EXPECT_FALSE(bad.IsValid(&why));
  EXPECT_NE(why.find("starts"), std::string::npos);
  GlobalAlgorithm algorithm;
  for (const char* name : {"crs2", "isres", "direct_l", "mlsl"}) {
    ASSERT_TRUE(FromString(name, &algorithm));
    EXPECT_EQ(std::string(ToString(algorithm)), name);
  }
  EXPECT_FALSE(FromString("simplex", &algorithm));
}

TEST(NloptFitter, GlobalSearchAgreesWithCeresOnHypoplasticData) {
  const std::vector<double> truth = testing::LondonClay();
  CalibrationProblem problem(
      {testing::MakeSyntheticDataset(ModelKind::kHypoplasticClay, truth, {})},
      ModelParameters::Defaults(ModelKind::kHypoplasticClay), PredictorOptions());
  const FitResult ceres =
      CeresFitter(CeresFitter::Options()).Fit(problem, {22.0, 0.1, 0.02, 1.3, 0.4});
  NloptFitter::Options options;
  const FitResult global = NloptFitter(options).Fit(problem);
  ExpectRecovered(global, truth);
  for (size_t k = 0; k < ceres.free_indices.size(); ++k) {
    const int i = ceres.free_indices[k];
    EXPECT_NEAR(global.values[i], ceres.values[i], 0.05 * ceres.standard_errors[k])
        << "parameter " << i;
  }
  EXPECT_NEAR(global.summary.final_cost, ceres.summary.final_cost, 1e-6 * ceres.summary.final_cost);
}

TEST(NloptFitter, EveryAlgorithmWithCeresPolishFindsTheCamClayOptimum) {
  const std::vector<double> truth = testing::CamClayTruth();
  testing::SyntheticOptions data;
  data.psi_epsilons_deg = {0, 30, 60, 90, 100, -30};
  CalibrationProblem problem(
      {testing::MakeSyntheticDataset(ModelKind::kModifiedCamClay, truth, data)},
      ModelParameters::Defaults(ModelKind::kModifiedCamClay), PredictorOptions());
  const FitResult ceres =
      CeresFitter(CeresFitter::Options()).Fit(problem, {30.0, 0.1, 0.01, 1.25, 0.3});
  for (GlobalAlgorithm algorithm : {GlobalAlgorithm::kCrs2, GlobalAlgorithm::kIsres,
                                    GlobalAlgorithm::kDirectL, GlobalAlgorithm::kMlsl}) {
    NloptFitter::Options options;
    options.algorithm = algorithm;
    options.starts = 2;
    options.max_evaluations = 1500;
    options.polish = LocalPolish::kCeres;
    const FitResult global = NloptFitter(options).Fit(problem);
    ASSERT_TRUE(global.summary.success()) << global.summary.Report();
    for (size_t k = 0; k < ceres.free_indices.size(); ++k) {
      const int i = ceres.free_indices[k];
      EXPECT_NEAR(global.values[i], ceres.values[i], 0.05 * ceres.standard_errors[k])
          << ToString(algorithm) << " parameter " << i;
    }
  }
}

TEST(CeresFitter, WarnsAboutParametersAtTheirBounds) {
  const std::vector<double> truth = testing::LondonClay();
  ModelParameters parameters = StartAwayFrom(ModelKind::kHypoplasticClay, truth);
  parameters.mutable_specs()[kLambdaStar].upper = 0.1;  // truth 0.11 is outside
  parameters.mutable_specs()[kLambdaStar].value = 0.09;
  CalibrationProblem problem(
      {testing::MakeSyntheticDataset(ModelKind::kHypoplasticClay, truth, {})}, parameters,
      PredictorOptions());
  const FitResult fit = CeresFitter(CeresFitter::Options()).Fit(problem);
  bool warned = false;
  for (const std::string& w : fit.warnings) {
    warned = warned || (w.find("lambda_star") != std::string::npos &&
                        w.find("upper bound") != std::string::npos);
  }
  EXPECT_TRUE(warned);
}

TEST(CeresFitter, WarnsAboutANearSingularCovariance) {
  // Only the NCL and the CSL: r changes nothing there (OCR_c = 2 for any r):
  // the problem refuses a free r. States at (numerically) one pressure cannot
  // separate λ* from N: the covariance says so.
  const std::vector<double> truth = testing::LondonClay();
  testing::SyntheticOptions data;
  ModelParameters parameters = StartAwayFrom(ModelKind::kHypoplasticClay, truth);
  data.psi_epsilons_deg = {0, 90};
  try {
    CalibrationProblem only_axes(
        {testing::MakeSyntheticDataset(ModelKind::kHypoplasticClay, truth, data)}, parameters,
        PredictorOptions());
    FAIL() << "accepted data that cannot identify r";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("parameter r cannot be identified"), std::string::npos)
        << error.what();
  }
  // κ* passes the pre-check (the CSL is not isotropic) but the hypoplastic
  // CSL does not depend on it (OCR_c = 2, ψ_σ(c) from φ_c): only the
  // covariance can tell.
  data.psi_epsilons_deg = {0, 90};
  ModelParameters two = ModelParameters::Defaults(ModelKind::kHypoplasticClay);
  for (int i = 0; i < kNumClayParameters; ++i) two.mutable_specs()[i].value = truth[i];
  two.mutable_specs()[kShearParameter].free = false;
  CalibrationProblem degenerate(
      {testing::MakeSyntheticDataset(ModelKind::kHypoplasticClay, truth, data)}, two,
      PredictorOptions());
  FitResult flat;
  flat.values = truth;
  ComputeUncertainty(degenerate, UncertaintyOptions(), &flat);
  bool warned = false;
  for (const std::string& w : flat.warnings) {
    warned = warned || (w.find("near-singular") != std::string::npos &&
                        w.find("kappa_star") != std::string::npos);
  }
  EXPECT_TRUE(warned) << ::testing::PrintToString(flat.warnings);
  EXPECT_TRUE(std::isnan(flat.standard_errors[kKappaStar]));
  EXPECT_TRUE(std::isfinite(flat.standard_errors[kLambdaStar]));
}

// The stall test on costs as a solve reports them: a fall of the deviance
// D = 2 cost/s² by less than 0.01 over ten steps ends it, with s² = 2 cost /
// dof where the uncertainties are scaled by it and 1 where they are not.
TEST(StallDetector, EndsACreepButNotASteadyFall) {
  CeresFitter::Options options;  // stall_deviance 0.01 over 10 steps
  // dof 100, cost 1000: s² = 20, a fall of 0.01 in D is 0.1 in cost.
  StallDetector creep(options, 100);
  int steps = 0;
  double cost = 1000.0;
  while (!creep.Stalled(cost) && steps < 1000) {
    cost -= 0.02 * std::pow(0.5, steps / 5.0);  // ever smaller steps
    ++steps;
  }
  EXPECT_LT(steps, 1000);
  EXPECT_NE(creep.why().find("Stalled"), std::string::npos) << creep.why();
  StallDetector steady(options, 100);
  cost = 1000.0;
  for (int k = 0; k < 200; ++k, cost -= 0.011) EXPECT_FALSE(steady.Stalled(cost)) << k;
  EXPECT_TRUE(steady.why().empty());
  // Unscaled (s² = 1): the same 0.011-per-step fall is 0.22 in D over ten steps.
  options.uncertainty.scale_by_residual_variance = false;
  StallDetector unscaled(options, 100);
  cost = 1000.0;
  for (int k = 0; k < 50; ++k, cost -= 0.011) EXPECT_FALSE(unscaled.Stalled(cost)) << k;
  StallDetector flat(options, 100);
  for (int k = 0; k < 10; ++k) EXPECT_FALSE(flat.Stalled(5.0)) << k;  // not ten steps yet
  EXPECT_TRUE(flat.Stalled(5.0));
  options.stall_deviance = 0;  // off
  StallDetector off(options, 100);
  for (int k = 0; k < 50; ++k) EXPECT_FALSE(off.Stalled(5.0)) << k;
}

// The sand model on states of a clay: a slow approach to its optimum, with
// alpha and beta at their bounds. The fit that ends as stalled ends where the
// one that runs to Ceres's tolerance does, to far less than its standard
// errors, in fewer iterations.
TEST(CeresFitter, AStalledFitEndsWhereTheFullyConvergedOneDoes) {
  testing::SyntheticOptions data;
  data.psi_epsilons_deg = {0, 30, 60, 90};
  const StateDataset clay =
      testing::MakeSyntheticDataset(ModelKind::kHypoplasticClay, testing::LondonClay(), data);
  const ModelParameters sand =
      ChooseParameters(ModelKind::kHypoplasticSand, {}, EstimateStartingValues({clay}), {clay});
  CalibrationProblem problem({clay}, sand, PredictorOptions());
  CeresFitter::Options full;
  full.stall_deviance = 0;
  const FitResult converged = CeresFitter(full).Fit(problem);
  const FitResult stalled = CeresFitter(CeresFitter::Options()).Fit(problem);
  ASSERT_EQ(converged.summary.termination, FitTermination::kConverged)
      << converged.summary.Report();
  ASSERT_EQ(stalled.summary.termination, FitTermination::kConverged) << stalled.summary.Report();
  EXPECT_NE(stalled.summary.message.find("Stalled"), std::string::npos) << stalled.summary.Report();
  EXPECT_LT(stalled.summary.iterations, converged.summary.iterations);
  EXPECT_LT(
      2 * (stalled.summary.final_cost - converged.summary.final_cost) / converged.residual_variance,
      0.01);
  ASSERT_EQ(converged.standard_errors.size(), converged.free_indices.size());
  for (size_t k = 0; k < converged.free_indices.size(); ++k) {
    const int i = converged.free_indices[k];
    if (!converged.Reported(k)) continue;  // at a bound
    EXPECT_LT(std::abs(stalled.values[i] - converged.values[i]), 0.1 * converged.standard_errors[k])
        << sand.specs()[i].name;
  }
}
}  // namespace
}  // namespace granasym::calibration
