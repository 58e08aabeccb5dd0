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
    path.ln_v.push_back(1.0 - 0.05 * x + gap);
    path.psi.push_back(20.0 - 400.0 * gap);
  }
  return path;
}

TEST(PathConvergence, PathsThatApproachOneLineJoinWhereTheirGapFallsBelowTheTolerance) {
  const PathSamples low = Path(1.0, 0.02, 0.5), high = Path(3.0, -0.02, 0.5);
  ConvergenceTolerance tolerance;
  tolerance.psi_sigma_deg = 1.0;
  tolerance.smoothing_lnp = 0.0;  // exact paths: no averaging
  const ConvergenceRow row = JoinPaths(low, high, true, tolerance);
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
  for (double& v : b.ln_v) v += 0.02;  // a parallel line 0.02 above
  EXPECT_EQ(JoinPaths(a, b, true, {}).status, "not_joined");
  const PathSamples c = Path(1.0, 0.0, 1.0);
  PathSamples d;
  d.x = {9.0, 10.0};
  d.ln_v = {0.5, 0.45};
  d.psi = {20.0, 20.0};
  EXPECT_EQ(JoinPaths(c, d, true, {}).status, "no_overlap");
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
