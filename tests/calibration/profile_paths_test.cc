// Profiles and the Pareto front with whole paths (issue 36 §3): a profile's
// refits keep the path datasets (κ* of the hypoplastic clay, which acts on
// neither the NCL nor the CSL, is determined by the unload–reload cycles
// alone); the front trades the asymptotic states against the whole paths
// when the paths disagree with the states; a fit left in a local minimum is
// refitted from the profile point that finds the better one.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "calibration/calibration_problem.h"
#include "calibration/ceres_fitter.h"
#include "calibration/pareto.h"
#include "calibration/profile_likelihood.h"
#include "path_data.h"
#include "synthetic_data.h"

namespace granasym::calibration {
namespace {

std::unique_ptr<ConstitutiveModel> Model(ModelKind kind, const std::vector<double>& values) {
  std::string why;
  std::unique_ptr<ConstitutiveModel> model = MakeModel(kind, values, &why);
  GRANASYM_CHECK(model) << why;
  return model;
}

// NCL and CSL states of `truth`, nearly without noise, at the DEM's
// uncertainties (0.5°, 0.002).
StateDataset NclCslStates(ModelKind kind, const std::vector<double>& truth) {
  testing::SyntheticOptions options;
  options.psi_sigma_noise_deg = 0.05;
  options.ln_volume_noise = 5e-4;
  options.psi_epsilons_deg = {0, 90};
  options.pressures_kpa = {50, 200, 800};
  options.stated_psi_sigma_deg = 0.5;
  options.stated_ln_volume = 0.002;
  return testing::MakeSyntheticDataset(kind, truth, options);
}

// κ* of the hypoplastic clay from the unload–reload cycles only: its profile
// (refits with the path) crosses the threshold on both sides around the
// truth. Profiles refitted without the paths (as before issue 36's fix)
// stay flat: the states alone do not move with κ*.
TEST(ProfileWithPaths, TheRefitsKeepThePathsThatDetermineKappa) {
  const std::vector<double> truth = testing::LondonClay();
  const auto model = Model(ModelKind::kHypoplasticClay, truth);
  ModelParameters parameters = ModelParameters::Defaults(ModelKind::kHypoplasticClay);
  for (int i = 0; i < kNumClayParameters; ++i) parameters.mutable_specs()[i].value = truth[i];
  parameters.mutable_specs()[kShearParameter].free = false;
  parameters.mutable_specs()[kKappaStar].value = 1.4 * truth[kKappaStar];
  parameters.mutable_specs()[kCriticalFrictionAngle].value = 1.05 * truth[0];
  const CalibrationProblem problem({NclCslStates(ModelKind::kHypoplasticClay, truth)}, parameters,
                                   PredictorOptions(), {testing::UnloadReloadCycles(*model)});
  const CeresFitter::Options ceres;
  const FitResult fit = CeresFitter(ceres).Fit(problem);
  ASSERT_EQ(fit.summary.termination, FitTermination::kConverged) << fit.summary.Report();
  EXPECT_NEAR(fit.values[kKappaStar], truth[kKappaStar], 0.02 * truth[kKappaStar]);
  ProfileOptions options;
  options.points_per_side = 4;
  const ProfileSet set = ProfileLikelihood(problem, fit, {}, ceres, options);
  ASSERT_EQ(set.profiles.size(), 4u);
  EXPECT_TRUE(set.warnings.empty()) << set.warnings.front();
  for (const ParameterProfile& p : set.profiles) {
    SCOPED_TRACE(p.Text());
    EXPECT_FALSE(p.flat());
    EXPECT_LE(p.lower, truth[p.parameter]);
    EXPECT_GE(p.upper, truth[p.parameter]);
    // The fit is the least cost of every profile (the refits see the same
    // problem): D ≥ 0 up to the refits' tolerance.
    for (const ProfilePoint& point : p.points) EXPECT_GT(point.statistic, -1e-3) << point.value;
  }
  const ParameterProfile& kappa = set.profiles[kKappaStar];
  EXPECT_EQ(kappa.name, "kappa_star");
  EXPECT_LT(kappa.upper / kappa.lower, 1.5) << kappa.Text();
  // The fast refits (forward differences, cost tolerance 1e-8: the default)
  // against exact ones (central differences, the fit's 1e-12): the same
  // intervals within 1e-3 of their width, with fewer evaluations.
  ProfileOptions exact_options = options;
  exact_options.fast_refits = false;
  const ProfileSet exact = ProfileLikelihood(problem, fit, {}, ceres, exact_options);
  long fast_evaluations = 0, exact_evaluations = 0;
  for (size_t k = 0; k < set.profiles.size(); ++k) {
    const ParameterProfile &a = set.profiles[k], &b = exact.profiles[k];
    SCOPED_TRACE(a.Text() + " against " + b.Text());
    const double width = b.upper - b.lower;
    EXPECT_NEAR(a.lower, b.lower, 1e-3 * width);
    EXPECT_NEAR(a.upper, b.upper, 1e-3 * width);
    fast_evaluations += a.evaluations;
    exact_evaluations += b.evaluations;
  }
  EXPECT_GT(fast_evaluations, 0);
  EXPECT_LT(fast_evaluations, 0.8 * exact_evaluations);
  std::printf("profiles with the cycles: %ld evaluations fast, %ld exact (%.2f s, %.2f s)\n",
              fast_evaluations, exact_evaluations, set.wall_seconds, exact.wall_seconds);
}

// States of `truth`; the unload–reload cycles and an isochoric path of a
// model with a larger φ_c and κ*: the asymptotic states and the whole paths
// pull φ_c and κ* apart.
TEST(ParetoFront, TradesTheAsymptoticStatesAgainstTheWholePaths) {
  const std::vector<double> truth = testing::CamClayTruth();
  std::vector<double> other = truth;
  other[kCriticalFrictionAngle] += 3.0;
  other[kKappaStar] *= 1.3;
  const auto path_model = Model(ModelKind::kModifiedCamClay, other);
  ModelParameters parameters = ModelParameters::Defaults(ModelKind::kModifiedCamClay);
  for (int i = 0; i < kNumClayParameters; ++i) parameters.mutable_specs()[i].value = truth[i];
  parameters.mutable_specs()[kShearParameter].free = false;
  const CalibrationProblem problem(
      {NclCslStates(ModelKind::kModifiedCamClay, truth)}, parameters, PredictorOptions(),
      {testing::UnloadReloadCycles(*path_model), testing::IsochoricPath(*path_model, 200, 1, 0.3)});
  const CeresFitter::Options ceres;
  const FitResult fit = CeresFitter(ceres).Fit(problem);
  ASSERT_TRUE(fit.summary.success()) << fit.summary.Report();
  const ResidualGroups groups = ChooseResidualGroups(problem);
  EXPECT_EQ(groups.names[0], "asymptotic_states");
  EXPECT_EQ(groups.names[1], "whole_paths");
  EXPECT_EQ(groups.path_group, 1);
  EXPECT_NE(groups.choice.find("whole paths"), std::string::npos) << groups.choice;
  // Every residual in one group: the states' and the paths'.
  EXPECT_EQ(groups.Residuals(problem, 0), problem.Group(ResidualGroup::kAsymptotic).count);
  EXPECT_EQ(groups.Residuals(problem, 1), problem.Group(ResidualGroup::kPath).count);
  const ParetoFront front = ComputeParetoFront(problem, fit, groups, ceres, ParetoOptions());
  ASSERT_TRUE(front.computed()) << front.not_computed;
  ASSERT_EQ(front.points.size(), 11u);
  EXPECT_TRUE(front.warnings.empty()) << front.warnings.front();
  EXPECT_TRUE(front.trade_off);
  EXPECT_TRUE(front.Monotone(1e-6)) << ParetoText(front, problem.parameters());
  // The ends: each group gains much over the other end, and φ_c moves from
  // the paths' value (w → 0, paths only) to the states' (w → 1).
  const ParetoPoint &first = front.points.front(), &last = front.points.back();
  EXPECT_LT(last.cost[0], 0.2 * first.cost[0]);
  EXPECT_LT(first.cost[1], 0.2 * last.cost[1]);
  EXPECT_NEAR(first.values[kCriticalFrictionAngle], other[kCriticalFrictionAngle], 0.5);
  EXPECT_NEAR(last.values[kCriticalFrictionAngle], truth[kCriticalFrictionAngle], 0.5);
  // The ordinary fit is the middle point, its group costs sum to the fit's.
  EXPECT_EQ(front.ordinary, 5);
  EXPECT_NEAR(front.points[5].cost[0] + front.points[5].cost[1], fit.summary.final_cost,
              1e-9 * fit.summary.final_cost);
  ASSERT_GE(front.compromise, 0);
  EXPECT_NE(front.rule.find("knee"), std::string::npos);
  const std::string text = ParetoText(front, problem.parameters());
  EXPECT_NE(text.find("asymptotic_states (group 0"), std::string::npos) << text;
  EXPECT_NE(text.find("groups traded: asymptotic states against whole paths"), std::string::npos)
      << text;
  const std::string csv = ParetoCsv(front, problem.parameters());
  EXPECT_EQ(csv.rfind("weight,cost_asymptotic_states,cost_whole_paths,", 0), 0u) << csv;
  // Without paths the states' two sides are traded, and the summary says so.
  const CalibrationProblem states({NclCslStates(ModelKind::kModifiedCamClay, truth)}, parameters,
                                  PredictorOptions());
  const ResidualGroups default_groups = ChooseResidualGroups(states);
  EXPECT_EQ(default_groups.names[0], "ncl_compression");
  EXPECT_EQ(default_groups.path_group, -1);
  EXPECT_NE(default_groups.choice.find("no whole paths"), std::string::npos);
}

// Two minima in ν of Modified Cam clay: an isochoric path of a model with
// ν = 0.05 and a drained path of one with ν = 0.45 (both from OCR 4, 5 %
// axial strain) pull the shear stiffness apart; the cost in ν has a local
// minimum near 0.44 and the global one near 0.18, with a low ridge at 0.41
// between them (the states, NCL and CSL with a misfit the model cannot
// remove, do not depend on ν and set the residual variance). A fit started
// at ν = 0.45 stops in the worse minimum; the profile of ν walks over the
// ridge and reaches lower costs, and the refit from there finds the better
// minimum.
TEST(ProfileAndRefit, RefitsFromTheProfileThatFindsTheBetterMinimum) {
  const ModelKind kind = ModelKind::kModifiedCamClay;
  const std::vector<double> truth = testing::CamClayTruth();
  std::vector<double> soft = truth, stiff = truth;
  soft[kShearParameter] = 0.05;
  stiff[kShearParameter] = 0.45;
  testing::SyntheticOptions options;
  options.psi_epsilons_deg = {0, 90};
  options.pressures_kpa = {50, 100, 200, 400, 800};
  options.psi_sigma_noise_deg = 0.5;
  options.ln_volume_noise = 0.005;
  StateDataset states = testing::MakeSyntheticDataset(kind, truth, options);
  for (AsymptoticStatePoint& point : states.points) {
    point.psi_sigma_uncertainty = 0.03 * kDegree;
    point.ln_volume_uncertainty = 0.0003;
  }
  ModelParameters parameters = ModelParameters::Defaults(kind);
  for (int i = 0; i < kNumClayParameters; ++i) {
    parameters.mutable_specs()[i].value = truth[i];
    parameters.mutable_specs()[i].free = i == kShearParameter || i == kCriticalFrictionAngle;
  }
  parameters.mutable_specs()[kShearParameter].value = 0.45;
  parameters.mutable_specs()[kCriticalFrictionAngle].value = 1.02 * truth[kCriticalFrictionAngle];
  const CalibrationProblem problem({states}, parameters, PredictorOptions(),
                                   {testing::IsochoricPath(*Model(kind, soft), 100, 4, 0.05),
                                    testing::DrainedPath(*Model(kind, stiff), 100, 4, 0.05)});
  const CeresFitter::Options ceres;
  const FitResult fit = CeresFitter(ceres).Fit(problem);
  ASSERT_EQ(fit.summary.termination, FitTermination::kConverged) << fit.summary.Report();
  // The worse minimum.
  EXPECT_GT(fit.values[kShearParameter], 0.42) << fit.values[kShearParameter];
  // Without restarts the profiles find the lower cost and only warn.
  ProfileOptions no_restart;
  no_restart.max_restarts = 0;
  const RefittedProfiles warned = ProfileAndRefit(problem, fit, {}, ceres, no_restart);
  EXPECT_TRUE(warned.restarts.empty());
  EXPECT_EQ(warned.fit.values, fit.values);
  ASSERT_FALSE(warned.profiles.warnings.empty());
  EXPECT_NE(warned.profiles.warnings.front().find("profile_lower_cost"), std::string::npos)
      << warned.profiles.warnings.front();
  // With them the fit moves to the better minimum, once.
  const RefittedProfiles refitted = ProfileAndRefit(problem, fit, {}, ceres, ProfileOptions());
  ASSERT_EQ(refitted.restarts.size(), 1u);
  const ProfileRestart& restart = refitted.restarts.front();
  EXPECT_TRUE(restart.kept);
  EXPECT_EQ(restart.parameter, "poisson_ratio");
  EXPECT_LT(restart.value, 0.40);
  EXPECT_DOUBLE_EQ(restart.cost_before, fit.summary.final_cost);
  EXPECT_LT(restart.cost_after, 0.95 * restart.cost_before);
  EXPECT_LE(restart.cost_after, restart.profile_cost);
  EXPECT_EQ(refitted.fit.summary.termination, FitTermination::kConverged);
  EXPECT_DOUBLE_EQ(refitted.fit.summary.final_cost, restart.cost_after);
  EXPECT_NEAR(refitted.fit.values[kShearParameter], 0.18, 0.05);
  // The refit keeps its uncertainties (the reported fit), and its profiles
  // are against it: no lower cost left.
  EXPECT_FALSE(refitted.fit.standard_errors.empty());
  EXPECT_EQ(refitted.profiles.fit_cost, restart.cost_after);
  for (const std::string& w : refitted.profiles.warnings) {
    EXPECT_EQ(w.find("profile_lower_cost"), std::string::npos) << w;
  }
  const std::string text = restart.Text();
  EXPECT_EQ(text.rfind("refitted from the poisson_ratio profile (poisson_ratio = ", 0), 0u) << text;
  EXPECT_NE(text.find(" -> "), std::string::npos) << text;
}

}  // namespace
}  // namespace granasym::calibration
