// Profile likelihoods and the Pareto front on synthetic data: profile
// intervals hold the true parameters and agree with the Jacobian's where the
// model is nearly linear; a parameter the data do not act on is flagged
// flat with the range it stays flat over; the front over two conflicting
// groups of states is monotone, and its compromise is the knee.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

#include "calibration/calibration_problem.h"
#include "calibration/ceres_fitter.h"
#include "calibration/identifiability.h"
#include "calibration/pareto.h"
#include "calibration/profile_likelihood.h"
#include "common/state_measures.h"
#include "constitutive/hypoplastic_sand.h"
#include "synthetic_data.h"

namespace granasym::calibration {
namespace {

ModelParameters StartNear(ModelKind kind, const std::vector<double>& truth) {
  ModelParameters parameters = ModelParameters::Defaults(kind);
  const double factors[] = {1.1, 0.9, 1.2, 0.98, 1.2};
  for (int i = 0; i < kNumClayParameters; ++i) {
    parameters.mutable_specs()[i].value = truth[i] * factors[i];
  }
  return parameters;
}

TEST(ProfileLikelihood, GridScaleFollowsTheBounds) {
  ParameterSpec spec;
  spec.lower = 1e-3;
  spec.upper = 0.5;
  EXPECT_TRUE(ProfiledOnLogScale(spec));  // λ*: bounds over two decades
  spec.lower = 5;
  spec.upper = 50;
  EXPECT_FALSE(ProfiledOnLogScale(spec));  // φ_c
  spec.lower = 0;
  spec.upper = 0.49;
  EXPECT_FALSE(ProfiledOnLogScale(spec));  // ν: not positive
  std::string why;
  ProfileOptions options;
  EXPECT_TRUE(options.IsValid(&why)) << why;
  options.points_per_side = 1;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("points_per_side"), std::string::npos) << why;
}

TEST(ProfileLikelihood, IntervalsHoldTheTruthAndMatchTheJacobiansNearTheOptimum) {
  const std::vector<double> truth = testing::LondonClay();
  const CalibrationProblem problem(
      {testing::MakeSyntheticDataset(ModelKind::kHypoplasticClay, truth, {})},
      StartNear(ModelKind::kHypoplasticClay, truth), PredictorOptions());
  const CeresFitter::Options ceres;
  const FitResult fit = CeresFitter(ceres).Fit(problem);
  ASSERT_EQ(fit.summary.termination, FitTermination::kConverged) << fit.summary.Report();
  const ProfileSet set = ProfileLikelihood(problem, fit, {}, ceres, ProfileOptions());
  ASSERT_EQ(set.profiles.size(), 5u);
  EXPECT_TRUE(set.warnings.empty()) << set.warnings.front();
  // With s² from the residuals: t²(0.975, m − n), near 3.84 for many residuals.
  EXPECT_GT(set.threshold, 3.84);
  EXPECT_LT(set.threshold, 4.1);
  for (size_t k = 0; k < set.profiles.size(); ++k) {
    const ParameterProfile& p = set.profiles[k];
    SCOPED_TRACE(p.name);
    EXPECT_EQ(p.parameter, fit.free_indices[k]);
    EXPECT_FALSE(p.flat()) << p.Text();
    EXPECT_EQ(p.lower_end, ProfileEnd::kCrossed);
    EXPECT_EQ(p.upper_end, ProfileEnd::kCrossed);
    EXPECT_LE(p.lower, truth[p.parameter]);
    EXPECT_GE(p.upper, truth[p.parameter]);
    EXPECT_LT(p.lower, p.optimum);
    EXPECT_GT(p.upper, p.optimum);
    // The grid: 2 × 8 points and the optimum, ascending; D = 0 at the optimum.
    EXPECT_GE(p.points.size(), 9u);
    EXPECT_LE(p.points.size(), 17u + 8u);
    for (size_t j = 1; j < p.points.size(); ++j) {
      EXPECT_GT(p.points[j].value, p.points[j - 1].value);
    }
    // The profile interval and the Jacobian's agree to a fifth of the latter's
    // width (small noise: the model is nearly linear over the interval),
    // except for r, which acts through K/G about as ln r does: its profile
    // reaches much farther above the optimum than below (here [0.31, 1.12]
    // around 0.49, where the Jacobian's symmetric interval ends at 0.76).
    ASSERT_TRUE(fit.Reported(k));
    const double width = fit.upper_95[k] - fit.lower_95[k];
    EXPECT_NEAR(p.lower, fit.lower_95[k], 0.2 * width);
    if (p.parameter == kShearParameter) {
      EXPECT_GT(p.upper - p.optimum, 2.0 * (p.optimum - p.lower));
      EXPECT_GT(p.upper, fit.upper_95[k] + 0.2 * width);
    } else {
      EXPECT_NEAR(p.upper, fit.upper_95[k], 0.2 * width);
    }
  }
  // The CSV has a row per grid point with the interval.
  const std::string csv = ProfilesCsv(set);
  EXPECT_EQ(csv.rfind("parameter,value,cost,statistic,threshold,converged,log_scale,", 0), 0u);
  size_t rows = 0;
  for (const ParameterProfile& p : set.profiles) rows += p.points.size();
  EXPECT_EQ(static_cast<size_t>(std::count(csv.begin(), csv.end(), '\n')), rows + 1);
  EXPECT_NE(ProfilesText(set).find("0 flat"), std::string::npos) << ProfilesText(set);
}

// Only the NCL and the CSL: above r ≈ 0.09 r acts on neither, so a fit with
// r fixed and its profile from the fixed value stay flat up to the bound;
// below it the model's critical state moves and the profile rises.
TEST(ProfileLikelihood, FlagsAParameterTheDataDoNotActOnAsFlat) {
  const std::vector<double> truth = testing::LondonClay();
  testing::SyntheticOptions options;
  options.psi_epsilons_deg = {0, 90};
  ModelParameters parameters = StartNear(ModelKind::kHypoplasticClay, truth);
  parameters.mutable_specs()[kShearParameter].free = false;
  parameters.mutable_specs()[kShearParameter].value = 0.4;
  parameters.mutable_specs()[kKappaStar].free = false;
  const CalibrationProblem problem(
      {testing::MakeSyntheticDataset(ModelKind::kHypoplasticClay, truth, options)}, parameters,
      PredictorOptions());
  const CeresFitter::Options ceres;
  const FitResult fit = CeresFitter(ceres).Fit(problem);
  ASSERT_TRUE(fit.summary.success()) << fit.summary.Report();
  ProfileOptions profile_options;
  profile_options.threads = 2;
  const ProfileSet set = ProfileLikelihood(problem, fit, {kShearParameter}, ceres, profile_options);
  ASSERT_EQ(set.profiles.size(), 4u);  // φ_c, λ*, N and r
  const ParameterProfile& r = set.profiles.back();
  EXPECT_EQ(r.name, "r");
  EXPECT_FALSE(r.fitted);
  EXPECT_TRUE(r.log_scale);
  EXPECT_TRUE(r.flat()) << r.Text();
  EXPECT_EQ(r.lower_end, ProfileEnd::kCrossed);
  EXPECT_EQ(r.upper_end, ProfileEnd::kBound);
  EXPECT_LT(r.lower, 0.1);
  EXPECT_GT(r.lower, 0.05);
  EXPECT_TRUE(std::isnan(r.upper));
  EXPECT_DOUBLE_EQ(r.flat_high, 3.0);  // the default upper bound
  EXPECT_NE(r.Text().find("to 3 (bound): not determined"), std::string::npos) << r.Text();
  for (const ProfilePoint& point : r.points) {
    if (point.value >= 0.1) {
      EXPECT_NEAR(point.statistic, 0.0, 1e-6) << point.value;
    }
  }
  for (size_t k = 0; k + 1 < set.profiles.size(); ++k) {
    EXPECT_FALSE(set.profiles[k].flat()) << set.profiles[k].Text();
  }
  // The same profiles on one thread.
  profile_options.threads = 1;
  const ProfileSet serial =
      ProfileLikelihood(problem, fit, {kShearParameter}, ceres, profile_options);
  EXPECT_EQ(ProfilesCsv(serial), ProfilesCsv(set));
}

// The sand's NCL (e_i) and CSL (e_c) do not depend on e_d0: the profile of
// e_d0 (fixed) stays flat upwards until the model is undefined just below
// e_c0 (e_d0 < e_c0, f_b > 0). The grid's first step, an eighth of the way to
// the bound 3, jumps past e_c0; bisected, the side ends within 1/64 of that
// step from the edge instead of at the fitted value.
TEST(ProfileLikelihood, ASideThatRunsIntoTheModelsDomainEndsAtItsEdge) {
  const std::vector<double> truth = {24.0, 1.7e5, 0.38, 0.46, 0.77, 0.83, 0.15, 1.0};
  std::string why;
  const auto model = MakeModel(ModelKind::kHypoplasticSand, truth, &why);
  ASSERT_TRUE(model) << why;
  const auto& sand = static_cast<const HypoplasticSand&>(*model);
  StateDataset axes;
  axes.name = "sand";
  axes.origin = "synthetic";
  for (double p : {50.0, 150.0, 450.0, 1000.0}) {
    for (const bool critical : {false, true}) {
      AsymptoticStatePoint point;
      point.kind = critical ? StateKind::kCsl : StateKind::kNcl;
      point.psi_epsilon = critical ? 0.5 * kPi : 0.0;
      point.mean_stress = p;
      point.void_ratio =
          critical ? sand.LimitVoidRatiosAt(p).critical : sand.LimitVoidRatiosAt(p).loosest;
      point.psi_sigma =
          critical ? std::atan(std::sqrt(2.0) / 3.0 * CriticalStateRatio(truth[0] * kDegree)) : 0;
      point.psi_sigma_uncertainty = 0.3 * kDegree;
      point.ln_volume_uncertainty = 0.002;
      point.source = "made";
      axes.points.push_back(point);
    }
  }
  ModelParameters parameters = ModelParameters::Defaults(ModelKind::kHypoplasticSand);
  for (size_t i = 0; i < truth.size(); ++i) {
    parameters.mutable_specs()[i].value = truth[i];
    parameters.mutable_specs()[i].free =
        i != kSandDensestVoidRatio && i != kSandPyknotropyExponent && i != kSandStiffnessExponent;
  }
  const CalibrationProblem problem({axes}, parameters, PredictorOptions());
  const CeresFitter::Options ceres;
  const FitResult fit = CeresFitter(ceres).Fit(problem);
  ASSERT_TRUE(fit.summary.success()) << fit.summary.Report();
  ProfileOptions profile_options;
  profile_options.threads = 1;
  const ProfileSet set =
      ProfileLikelihood(problem, fit, {kSandDensestVoidRatio}, ceres, profile_options);
  ASSERT_EQ(set.profiles.size(), 6u);  // the 5 fitted and e_d0, in parameter order
  const ParameterProfile& e_d0 = set.profiles[kSandDensestVoidRatio];
  ASSERT_EQ(e_d0.parameter, kSandDensestVoidRatio);
  EXPECT_FALSE(e_d0.fitted);
  EXPECT_TRUE(e_d0.flat()) << e_d0.Text();
  EXPECT_EQ(e_d0.upper_end, ProfileEnd::kDomain) << e_d0.Text();
  EXPECT_NE(e_d0.failure.find("e_d0"), std::string::npos) << e_d0.failure;
  const ProfilePoint& last = e_d0.points.back();
  const double e_c0 = last.values[kSandCriticalVoidRatio];
  EXPECT_LT(last.value, e_c0);
  const double step = (3.0 - 0.46) / profile_options.points_per_side;
  EXPECT_GT(last.value, e_c0 - step / 64 - 1e-3) << e_d0.Text() << "; e_c0 " << e_c0;
  EXPECT_DOUBLE_EQ(e_d0.flat_high, last.value);
}

// r fixed as undetermined at 0.02, far from the data's 0.4: its profile at
// the fit rejects that value, so RunCalibration's last step frees it, refits
// from the profile's least cost and profiles again. With states on the axes
// only, the problem refuses a free r: it stays fixed, said so.
TEST(ProfileLikelihood, AFixedValueTheProfileRejectsIsFreedAndRefitted) {
  const std::vector<double> truth = testing::LondonClay();
  ModelParameters parameters = StartNear(ModelKind::kHypoplasticClay, truth);
  parameters.mutable_specs()[kShearParameter].free = false;
  parameters.mutable_specs()[kShearParameter].value = 0.02;
  const std::vector<StateDataset> datasets = {
      testing::MakeSyntheticDataset(ModelKind::kHypoplasticClay, truth, {})};
  CalibrationConfig config;
  config.model = ModelKind::kHypoplasticClay;
  config.profiles.threads = 2;
  CalibrationRun run;
  run.problem = std::make_unique<CalibrationProblem>(datasets, parameters, PredictorOptions());
  run.fits.push_back(CeresFitter(config.ceres).Fit(*run.problem));
  run.kept = 0;
  ASSERT_TRUE(run.fits[0].summary.success()) << run.fits[0].summary.Report();
  const double fixed_cost = run.fits[0].summary.final_cost;
  run.profiles = ProfileLikelihood(*run.problem, run.fits[0], {kShearParameter}, config.ceres,
                                   config.profiles);
  run.undetermined = {"r fixed at its start value 0.02: the data do not determine it (...)"};
  std::vector<bool> undetermined(parameters.specs().size(), false);
  undetermined[kShearParameter] = true;
  FreeRejectedFixedValues(config, datasets, {}, &parameters, &undetermined, &run);
  ASSERT_EQ(run.freed.size(), 1u);
  EXPECT_EQ(run.freed[0].find("r: fixed at 0.02 as undetermined"), 0u) << run.freed[0];
  EXPECT_TRUE(run.undetermined.empty());
  EXPECT_FALSE(undetermined[kShearParameter]);
  EXPECT_TRUE(run.problem->parameters().specs()[kShearParameter].free);
  const FitResult& refit = *run.kept_fit();
  ASSERT_TRUE(refit.summary.success()) << refit.summary.Report();
  // A significant fall.
  EXPECT_GT(2 * (fixed_cost - refit.summary.final_cost) / run.profiles.residual_variance,
            run.profiles.threshold);
  EXPECT_GT(refit.values[kShearParameter], 0.2);
  EXPECT_LT(refit.values[kShearParameter], 0.8);
  // The profiles are of the refit, r among the fitted ones.
  EXPECT_DOUBLE_EQ(run.profiles.fit_cost, refit.summary.final_cost);
  const ParameterProfile& r = run.profiles.profiles.back();
  EXPECT_EQ(r.name, "r");
  EXPECT_TRUE(r.fitted);
  // Nothing left to free: a second call changes nothing.
  FreeRejectedFixedValues(config, datasets, {}, &parameters, &undetermined, &run);
  EXPECT_EQ(run.freed.size(), 1u);

  testing::SyntheticOptions axes;
  axes.psi_epsilons_deg = {0, 90};
  const std::vector<StateDataset> on_axes = {
      testing::MakeSyntheticDataset(ModelKind::kHypoplasticClay, truth, axes)};
  ModelParameters fixed = StartNear(ModelKind::kHypoplasticClay, truth);
  fixed.mutable_specs()[kShearParameter].free = false;
  fixed.mutable_specs()[kShearParameter].value = 0.02;
  fixed.mutable_specs()[kKappaStar].free = false;
  CalibrationRun refused;
  refused.problem = std::make_unique<CalibrationProblem>(on_axes, fixed, PredictorOptions());
  refused.fits.push_back(CeresFitter(config.ceres).Fit(*refused.problem));
  refused.kept = 0;
  refused.profiles = ProfileLikelihood(*refused.problem, refused.fits[0], {kShearParameter},
                                       config.ceres, config.profiles);
  refused.undetermined = {"r fixed at its start value 0.02: the data do not determine it (...)"};
  undetermined.assign(fixed.specs().size(), false);
  undetermined[kShearParameter] = true;
  FreeRejectedFixedValues(config, on_axes, {}, &fixed, &undetermined, &refused);
  ASSERT_EQ(refused.freed.size(), 1u);
  EXPECT_NE(refused.freed[0].find("r stays fixed at 0.02"), std::string::npos) << refused.freed[0];
  EXPECT_NE(refused.freed[0].find("cannot be identified"), std::string::npos) << refused.freed[0];
  EXPECT_TRUE(undetermined[kShearParameter]);
  EXPECT_FALSE(fixed.specs()[kShearParameter].free);
  EXPECT_EQ(refused.undetermined.size(), 1u);
}

// κ* acts on neither the NCL nor the hypoplastic CSL (OCR 2 whatever κ*): the
// Jacobian is rank-deficient in κ*'s direction, said instead of correlations.
TEST(FitResult, NamesTheNullDirectionsOfARankDeficientJacobian) {
  const std::vector<double> truth = testing::LondonClay();
  testing::SyntheticOptions options;
  options.psi_epsilons_deg = {0, 90};
  ModelParameters parameters = StartNear(ModelKind::kHypoplasticClay, truth);
  parameters.mutable_specs()[kShearParameter].free = false;
  const CalibrationProblem problem(
      {testing::MakeSyntheticDataset(ModelKind::kHypoplasticClay, truth, options)}, parameters,
      PredictorOptions());
  const FitResult fit = CeresFitter(CeresFitter::Options()).Fit(problem);
  ASSERT_TRUE(fit.summary.success()) << fit.summary.Report();
  ASSERT_EQ(fit.null_directions.size(), 1u);
  const NullDirection& null = fit.null_directions.front();
  ASSERT_EQ(null.components.size(), 4u);
  EXPECT_NEAR(std::abs(null.components[kKappaStar]), 1.0, 1e-6);
  EXPECT_EQ(null.Text(problem.parameters(), fit.free_indices), "1.00 kappa_star");
  EXPECT_LT(null.singular_ratio, 1e-8);
  // The full-rank fit of every direction has none.
  const CalibrationProblem full(
      {testing::MakeSyntheticDataset(ModelKind::kHypoplasticClay, truth, {})},
      StartNear(ModelKind::kHypoplasticClay, truth), PredictorOptions());
  EXPECT_TRUE(CeresFitter(CeresFitter::Options()).Fit(full).null_directions.empty());
  // A direction of two parameters, signed by its largest component.
  NullDirection pair;
  pair.components = {0.0, -0.8, 0.0, 0.6};
  EXPECT_EQ(pair.Text(problem.parameters(), fit.free_indices),
            "0.80 lambda_star - 0.60 n_intercept");
}

// Data whose critical states lie above the model's CSL (OCR_c of the DEM
// below 2): the compression side and the critical side pull φ_c, λ*, N apart.
StateDataset ConflictingData() {
  const std::vector<double> truth = testing::LondonClay();
  testing::SyntheticOptions options;
  options.psi_epsilons_deg = {0, 30, 60, 90, 100, 110};
  options.seed = 11;
  StateDataset data = testing::MakeSyntheticDataset(ModelKind::kHypoplasticClay, truth, options);
  for (AsymptoticStatePoint& point : data.points) {
    if (point.kind == StateKind::kCsl || point.kind == StateKind::kExtension) {
      point.void_ratio = std::expm1(std::log1p(point.void_ratio) + 0.03);
    }
  }
  return data;
}

// The conflicting data fitted from near London clay, with its two default
// residual groups.
struct ConflictingFit {
  CalibrationProblem problem{{ConflictingData()},
                             StartNear(ModelKind::kHypoplasticClay, testing::LondonClay()),
                             PredictorOptions()};
  CeresFitter::Options ceres;
  FitResult fit = CeresFitter(ceres).Fit(problem);
  ResidualGroups groups = DefaultResidualGroups(problem);
};

TEST(ParetoFront, IsMonotoneOnConflictingDataWithTheKneeAsCompromise) {
  const ConflictingFit conflicting;
  const auto& [problem, ceres, fit, groups] = conflicting;
  ASSERT_TRUE(fit.summary.success()) << fit.summary.Report();
  EXPECT_EQ(groups.Residuals(problem, 0) + groups.Residuals(problem, 1), problem.num_residuals());
  const ParetoFront front = ComputeParetoFront(problem, fit, groups, ceres, ParetoOptions());
  ASSERT_TRUE(front.computed()) << front.not_computed;
  // The uniform sweep's 11 points, and more where they were fewer than 10 distinct ones.
  ASSERT_GE(front.points.size(), 11u);
  EXPECT_GE(front.distinct, 10) << ParetoText(front, problem.parameters());
  EXPECT_TRUE(front.warnings.empty()) << front.warnings.front();
  EXPECT_TRUE(front.trade_off);
  EXPECT_TRUE(front.Monotone(1e-6)) << ParetoText(front, problem.parameters());
  // A real conflict: each end gains much for its group over the other end.
  const ParetoPoint &first = front.points.front(), &last = front.points.back();
  EXPECT_LT(first.weight, 0.01);
  EXPECT_GT(last.weight, 0.99);
  EXPECT_LT(last.cost[0], 0.5 * first.cost[0]);
  EXPECT_LT(first.cost[1], 0.5 * last.cost[1]);
  // The ordinary fit is the middle point; the compromise is the knee.
  ASSERT_GE(front.ordinary, 0);
  const ParetoPoint& ordinary = front.points[front.ordinary];
  EXPECT_DOUBLE_EQ(ordinary.weight, 0.5);
  EXPECT_FALSE(ordinary.refined);
  EXPECT_NEAR(ordinary.cost[0] + ordinary.cost[1], fit.summary.final_cost,
              1e-9 * fit.summary.final_cost);
  ASSERT_GE(front.compromise, 0);
  const auto distance = [](const ParetoPoint& p) {
    return std::hypot(p.normalised[0], p.normalised[1]);
  };
  for (const ParetoPoint& p : front.points) {
    EXPECT_GE(distance(p), distance(front.points[front.compromise]));
    for (int g = 0; g < 2; ++g) {
      EXPECT_GE(p.normalised[g], 0.0);
      EXPECT_LE(p.normalised[g], 1.0);
    }
  }
  EXPECT_NE(front.rule.find("knee"), std::string::npos);
  const std::string csv = ParetoCsv(front, problem.parameters());
  EXPECT_EQ(csv.rfind("weight,cost_ncl_compression,cost_csl_extension,", 0), 0u) << csv;
  EXPECT_NE(csv.find(",ordinary,distinct,weight_low,weight_high,label,labelled,refined,group_0,"
                     "group_1,phi_c_deg,"),
            std::string::npos)
      << csv;
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), static_cast<long>(front.points.size()) + 1);
}

// A uniform grid out to w/(1 − w) = 1e±8 returns the groups' own optima at
// several weights of each end: those are merged into one point labelled
// with their weight range, and the front is refined where it moves (bisecting
// between neighbouring distinct points) until it has 10 distinct points,
// still monotone; one label per distinct point at most, none drawn on top of
// another.
TEST(ParetoFront, MergesDuplicatesOfAUniformGridAndRefinesToTenDistinctPoints) {
  const ConflictingFit conflicting;
  const auto& [problem, ceres, fit, groups] = conflicting;
  ASSERT_TRUE(fit.summary.success()) << fit.summary.Report();
  ParetoOptions options;
  options.max_weight_ratio = 1e8;
  options.min_distinct = 0;  // the uniform grid alone
  const ParetoFront uniform = ComputeParetoFront(problem, fit, groups, ceres, options);
  ASSERT_TRUE(uniform.computed()) << uniform.not_computed;
  ASSERT_EQ(uniform.points.size(), 11u);
  EXPECT_EQ(uniform.refinements, 0);
  EXPECT_LT(uniform.distinct, 10) << ParetoText(uniform, problem.parameters());
  // The first point stands for a range of weights, labelled so.
  const ParetoPoint& end = uniform.points.front();
  EXPECT_LT(end.weight_low, end.weight_high);
  EXPECT_EQ(end.Label().find("w = 1e-08 to "), 0u) << end.Label();
  EXPECT_EQ(uniform.points[1].distinct, 0);
  EXPECT_FALSE(uniform.points[1].labelled);

  options.min_distinct = 10;
  const ParetoFront front = ComputeParetoFront(problem, fit, groups, ceres, options);
  const std::string text = ParetoText(front, problem.parameters());
  ASSERT_TRUE(front.computed()) << front.not_computed;
  EXPECT_GE(front.distinct, 10) << text;
  EXPECT_GT(front.refinements, 0);
  EXPECT_LE(front.refinements, options.max_refinements);
  EXPECT_EQ(front.points.size(), 11u + static_cast<size_t>(front.refinements));
  EXPECT_TRUE(front.Monotone(1e-6)) << text;
  for (size_t j = 1; j < front.points.size(); ++j) {
    EXPECT_LT(front.points[j - 1].weight, front.points[j].weight);
    EXPECT_GE(front.points[j].distinct, front.points[j - 1].distinct);
  }
  EXPECT_EQ(front.points.back().distinct, front.distinct - 1);
  // One label at most per distinct point, the compromise's and the ends' drawn.
  std::vector<int> labels(static_cast<size_t>(front.distinct), 0);
  for (const ParetoPoint& p : front.points) labels[p.distinct] += p.labelled ? 1 : 0;
  for (int count : labels) EXPECT_LE(count, 1);
  EXPECT_EQ(labels.front(), 1);
  EXPECT_EQ(labels.back(), 1);
  EXPECT_EQ(labels[front.points[front.compromise].distinct], 1);
  EXPECT_NE(
      text.find(fmt::format("distinct points: {} of {}", front.distinct, front.points.size())),
      std::string::npos)
      << text;
  EXPECT_NE(text.find("refinement: the uniform sweep gave fewer than 10 distinct points"),
            std::string::npos)
      << text;
  // The same front whatever the threads: two refinements at a time, each from
  // its own start.
  const ParetoFront again = ComputeParetoFront(problem, fit, groups, ceres, options);
  ASSERT_EQ(again.points.size(), front.points.size());
  for (size_t j = 0; j < front.points.size(); ++j) {
    EXPECT_EQ(again.points[j].weight, front.points[j].weight);
    EXPECT_EQ(again.points[j].cost, front.points[j].cost);
  }
}

TEST(ParetoFront, SaysWhyWithoutASecondGroup) {
  const std::vector<double> truth = testing::LondonClay();
  testing::SyntheticOptions options;
  options.psi_epsilons_deg = {0, 30, 60};
  ModelParameters parameters = StartNear(ModelKind::kHypoplasticClay, truth);
  parameters.mutable_specs()[kShearParameter].free = false;
  const CalibrationProblem problem(
      {testing::MakeSyntheticDataset(ModelKind::kHypoplasticClay, truth, options)}, parameters,
      PredictorOptions());
  const FitResult fit = CeresFitter(CeresFitter::Options()).Fit(problem);
  const ParetoFront front = ComputeParetoFront(problem, fit, DefaultResidualGroups(problem),
                                               CeresFitter::Options(), ParetoOptions());
  EXPECT_FALSE(front.computed());
  EXPECT_NE(front.not_computed.find("csl_extension"), std::string::npos) << front.not_computed;
  std::string why;
  ParetoOptions even;
  even.points = 10;
  EXPECT_FALSE(even.IsValid(&why));
  EXPECT_NE(why.find("odd"), std::string::npos);
}

}  // namespace
}  // namespace granasym::calibration
