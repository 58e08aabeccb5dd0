// Starting values from NCL regression, critical stress ratio and unloading.
#include "calibration/starting_values.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/state_measures.h"

namespace granasym::calibration {
namespace {

AsymptoticStatePoint Point(StateKind kind, double p, double ln_v, double psi_sigma) {
  AsymptoticStatePoint point;
  point.kind = kind;
  point.mean_stress = p;
  point.void_ratio = std::exp(ln_v) - 1;
  point.psi_sigma = psi_sigma;
  point.psi_epsilon = kind == StateKind::kCsl ? 0.5 * kPi : kind == StateKind::kUnloading ? kPi : 0;
  return point;
}

TEST(StartingValues, RecoverExactLinesAndTheCriticalStateAngle) {
  StateDataset d;
  const double lambda = 0.11, n = 1.375, kappa = 0.016, phi = 22.6 * kDegree;
  for (double p : {50.0, 100.0, 200.0, 400.0}) {
    d.points.push_back(Point(StateKind::kNcl, p, n - lambda * std::log(p), 0.0));
    d.points.push_back(
        Point(StateKind::kCsl, p, n - lambda * std::log(2 * p), CriticalStatePsiSigma(phi)));
  }
  for (double p : {400.0, 200.0, 100.0}) {
    d.points.push_back(Point(StateKind::kUnloading, p, 0.7 - kappa * std::log(p), 0.0));
  }
  const StartingValues s = EstimateStartingValues({d});
  EXPECT_TRUE(s.lambda_star.from_data);
  EXPECT_NEAR(s.lambda_star.value, lambda, 1e-12);
  EXPECT_NEAR(s.n_intercept.value, n, 1e-12);
  EXPECT_NEAR(s.lambda_star.standard_error, 0.0, 1e-10);
  EXPECT_EQ(s.lambda_star.points, 4);
  EXPECT_NEAR(s.critical_friction_angle_deg.value, 22.6, 1e-10);
  EXPECT_TRUE(s.kappa_star.from_data);
  EXPECT_NEAR(s.kappa_star.value, kappa, 1e-12);
  EXPECT_NE(s.Report().find("lambda_star"), std::string::npos);
}

TEST(StartingValues, ReportStandardErrorsOfNoisyData) {
  StateDataset d;
  const double noise[] = {0.003, -0.002, 0.001, -0.003, 0.002};
  int k = 0;
  for (double p : {50.0, 100.0, 200.0, 400.0, 800.0}) {
    d.points.push_back(Point(StateKind::kNcl, p, 1.4 - 0.1 * std::log(p) + noise[k++], 0.0));
  }
  const StartingValues s = EstimateStartingValues({d});
  EXPECT_GT(s.lambda_star.standard_error, 0.0);
  EXPECT_LT(std::abs(s.lambda_star.value - 0.1), 3 * s.lambda_star.standard_error + 1e-4);
}

TEST(StartingValues, SayWhatIsAssumedWithoutData) {
  StateDataset d;
  d.points.push_back(Point(StateKind::kNcl, 100, 0.6, 0.0));
  const StartingValues s = EstimateStartingValues({d});
  EXPECT_FALSE(s.lambda_star.from_data);
  EXPECT_NE(s.lambda_star.note.find("fewer than 2 NCL points"), std::string::npos);
  EXPECT_FALSE(s.critical_friction_angle_deg.from_data);
  EXPECT_NE(s.kappa_star.note.find("no unloading"), std::string::npos);
}

// The NCL at one p (a rate study's ψ_ε = 0° paths all end at the stress
// cap): the slope from the falling CSL, the intercept through the NCL point.
TEST(StartingValues, TakeTheCslSlopeWhenTheNclHasOnePressure) {
  StateDataset d;
  const double lambda = 0.05, n = 0.9, phi = 21 * kDegree;
  d.points.push_back(Point(StateKind::kNcl, 2500, n - lambda * std::log(2500), 0.0));
  for (double p : {30.0, 130.0, 700.0}) {
    d.points.push_back(
        Point(StateKind::kCsl, p, n - lambda * std::log(2 * p), CriticalStatePsiSigma(phi)));
  }
  StartingValues s = EstimateStartingValues({d});
  EXPECT_TRUE(s.lambda_star.from_data);
  EXPECT_NEAR(s.lambda_star.value, lambda, 1e-12);
  EXPECT_NE(s.lambda_star.note.find("the CSL regression"), std::string::npos) << s.lambda_star.note;
  EXPECT_FALSE(s.n_intercept.from_data);
  EXPECT_NEAR(s.n_intercept.value, n, 1e-12);
  // A CSL that does not fall gives no slope: assumed, the intercept still
  // through the NCL point.
  for (AsymptoticStatePoint& point : d.points) {
    if (point.kind == StateKind::kCsl) point.void_ratio = 0.6;
  }
  s = EstimateStartingValues({d});
  EXPECT_FALSE(s.lambda_star.from_data);
  EXPECT_NEAR(s.n_intercept.value, n - lambda * std::log(2500) + 0.1 * std::log(2500), 1e-12);
}

}  // namespace
}  // namespace granasym::calibration
