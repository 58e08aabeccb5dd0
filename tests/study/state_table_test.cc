#include "study/state_table.h"

#include <gtest/gtest.h>

#include <cmath>

namespace granasym::study {
namespace {

// Two compression paths approaching the line ln(1+e) = 1 − 0.05 ln p and
// ψ_σ = 20° from different starts: each deviates by an amount that decays
// with ln p from its own start.
PathSamples Path(double start_lnp, double offset, double decay) {
  PathSamples path;
  for (double x = start_lnp; x <= 8.0; x += 0.01) {
    const double gap = offset * std::exp(-(x - start_lnp) / decay);
    path.x.push_back(x);
    path.y.push_back(1.0 - 0.05 * x + gap);
    path.psi.push_back(20.0 - 400.0 * gap);
  }
  return path;
}

TEST(PathConvergence, PathsThatApproachOneLineJoinWhereTheirGapFallsBelowTheTolerance) {
  const PathSamples low = Path(1.0, 0.02, 0.5), high = Path(3.0, -0.02, 0.5);
  ConvergenceTolerance tolerance;
  tolerance.psi_sigma_deg = 1.0;
  tolerance.smoothing_lnp = 0.0;  // exact paths: no averaging
  const ConvergenceRow row = JoinPaths(low, high, tolerance);
  ASSERT_EQ(row.status, "joined");
  // The ψ_σ gap 400 (g_low + |g_high|) < 1 deg decides (the ln(1+e) gap is
  // within 0.005 from x = 3 + 0.5 ln 4 = 3.69): |g_high| = 0.02 exp(−(x−3)/0.5)
  // falls below 1/400 at x = 3 + 0.5 ln 8 = 4.04 (g_low is below 1e-4 there),
  // and the grid over [3, 8] has a point every 0.128.
  EXPECT_NEAR(std::log(row.joined_at_p_kpa), 4.1, 0.15);
  EXPECT_NEAR(row.psi_sigma_deg, 20.0, 1.0);
  EXPECT_NEAR(row.ln_1_plus_e, 1.0 - 0.05 * std::log(row.joined_at_p_kpa), 0.005);
}

TEST(PathConvergence, ParallelPathsThatStayApartDoNotJoin) {
  const PathSamples a = Path(1.0, 0.0, 1.0);
  PathSamples b = Path(2.0, 0.0, 1.0);
  for (double& v : b.y) v += 0.02;  // a parallel line 0.02 above
  EXPECT_EQ(JoinPaths(a, b, {}).status, "not_joined");
  const PathSamples c = Path(1.0, 0.0, 1.0);
  PathSamples d;
  d.x = {9.0, 10.0};
  d.y = {0.5, 0.45};
  d.psi = {20.0, 20.0};
  EXPECT_EQ(JoinPaths(c, d, {}).status, "no_overlap");
}

// Two extension paths of the paper's rate: each falls steeply from its NC
// state and then runs nearly vertically in ln(1+e)–ln p (a dense flow, p
// about 1 kPa while ln(1+e) rises), from different starting void ratios; on
// a common ln(1+e) they agree once both are in the flow. At a common ln p
// they never would (p barely moves along the flow).
PathSamples Flow(double start_v, double start_lnp) {
  PathSamples path;
  for (double x = start_v; x <= 0.75; x += 0.0005) {
    const double fall = std::max(0.0, 1.0 - (x - start_v) / 0.02);  // the fall: 0.02 of ln(1+e)
    path.x.push_back(x);
    path.y.push_back(fall * start_lnp + 0.1 * std::sin(900.0 * x) - 0.5 * (x - 0.5));
    path.psi.push_back(40.0 - 30.0 * fall);
  }
  return path;
}

TEST(PathConvergence, ExtensionFlowsJoinAtACommonVoidRatio) {
  const PathSamples from500 = Flow(0.530, std::log(500.0));
  const PathSamples from1000 = Flow(0.511, std::log(1000.0));
  const ConvergenceRow row = JoinExtensionPaths(from500, from1000, {});
  ASSERT_EQ(row.status, "joined");
  // The path from 500 kPa is in its flow from ln(1+e) = 0.55 on.
  EXPECT_NEAR(row.ln_1_plus_e, 0.55, 0.01);
  EXPECT_NEAR(row.psi_sigma_deg, 40.0, 2.0);
  EXPECT_NEAR(std::log(row.joined_at_p_kpa), -0.5 * (row.ln_1_plus_e - 0.5), 0.1);
  EXPECT_GT(row.overlap_from_p_kpa, row.overlap_to_p_kpa);  // p falls along the overlap
  // Flows of different ψ_ε lie apart in ln p (OCR grows with ψ_ε): not joined.
  PathSamples lower = from500;
  for (double& y : lower.y) y -= 0.6;
  EXPECT_EQ(JoinExtensionPaths(lower, from1000, {}).status, "not_joined");
}

TEST(Replicates, MeanAndStudentIntervalOfTheMean) {
  // n = 3: mean 2, s = 1, t(0.975, 2) = 4.303: half-width 4.303 / sqrt(3).
  const Interval three = MeanInterval95({1.0, 2.0, 3.0});
  EXPECT_DOUBLE_EQ(three.mean, 2.0);
  EXPECT_NEAR(three.half_width, 4.303 / std::sqrt(3.0), 1e-12);
  // n = 2: t(0.975, 1) = 12.706, s = sqrt(2) * 0.5.
  const Interval two = MeanInterval95({10.0, 11.0});
  EXPECT_NEAR(two.half_width, 12.706 * std::sqrt(0.5) / std::sqrt(2.0), 1e-12);
  EXPECT_TRUE(std::isnan(MeanInterval95({5.0}).half_width));
  EXPECT_TRUE(std::isnan(MeanInterval95({}).mean));
}

}  // namespace
}  // namespace granasym::study
