// The asymptotic-state detector of dem/asymptote_detector.h on synthetic
// series with known ψ_σ, ln p and ln(1 + e), against the criterion stated in
// dem/scene.h (AsymptoteCriterion).
#include "dem/asymptote_detector.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>

#include "common/state_measures.h"

namespace granasym::dem {
namespace {

using Sample = AsymptoteDetector::Sample;
using Curve = std::function<double(double)>;  // a state measure as a function of strain

// A state measure of the synthetic series.
struct Series {
  Curve psi_sigma = [](double) { return 35.0 * kDegree; };
  Curve log_p = [](double) { return std::log(100.0); };
  Curve log_volume = [](double) { return std::log(1.6); };
};

Sample At(const Series& series, double strain) {
  return {strain, series.psi_sigma(strain), series.log_p(strain), series.log_volume(strain)};
}

// Adds samples k = first .. last (inclusive) at strain k * spacing.
void Feed(AsymptoteDetector& detector, const Series& series, int first, int last, double spacing) {
  for (int k = first; k <= last; ++k) detector.Add(At(series, k * spacing));
}

// The default criterion: window 0.1 sampled every 2e-3 (51 samples per window).
const AsymptoteCriterion kCriterion{};
const double kSpacing = kCriterion.sample_strain;
constexpr int kWindowSamples = 50;  // intervals per window

// A state moving parallel to an asymptotic line: ln p = ln p0 + a ε and
// ln(1 + e) = ln(1 + e0) − λ* (ln p − ln p0).
Series ParallelToALine(double slope_lnp, double lambda_star) {
  Series series;
  series.log_p = [slope_lnp](double strain) { return std::log(80.0) + slope_lnp * strain; };
  series.log_volume = [slope_lnp, lambda_star](double strain) {
    return std::log(1.7) - lambda_star * slope_lnp * strain;
  };
  return series;
}

TEST(AsymptoteDetector, DefaultCriterionIsTheDocumentedOne) {
  EXPECT_EQ(kCriterion.sample_strain, 2e-3);
  EXPECT_EQ(kCriterion.window_strain, 0.1);
  EXPECT_EQ(kCriterion.psi_tolerance_deg, 0.5);
  EXPECT_EQ(kCriterion.lnp_tolerance, 0.02);
  EXPECT_EQ(AsymptoteDetector().criterion().window_strain, kCriterion.window_strain);
}

TEST(AsymptoteDetector, StationaryPsiWithLnPLinearInStrainIsDetected) {
  // Compression (p rising) and extension (p falling) paths parallel to a line.
  for (const double slope_lnp : {2.5, -1.5}) {
    const double lambda_star = 0.045;
    AsymptoteDetector detector(kCriterion);
    Feed(detector, ParallelToALine(slope_lnp, lambda_star), 0, 3 * kWindowSamples, kSpacing);
    ASSERT_TRUE(detector.ready());
    const AsymptoteDetector::Result result = detector.Evaluate();
    EXPECT_TRUE(result.detected) << slope_lnp;
    EXPECT_NEAR(result.slope_lnp, slope_lnp, 1e-9);
    EXPECT_NEAR(result.slope_lnv_lnp, -lambda_star, 1e-9);
    EXPECT_NEAR(result.psi_sigma, 35.0 * kDegree, 1e-12);
    EXPECT_NEAR(result.psi_change_deg, 0.0, 1e-9);
    EXPECT_NEAR(result.lnp_half_difference, 0.0, 1e-9);
  }
}

TEST(AsymptoteDetector, SmallPsiFluctuationsAroundAStationaryValueAreDetected) {
  // DEM series are noisy: a ±0.2° oscillation about 40° with no trend.
  Series series = ParallelToALine(1.2, 0.03);
  series.psi_sigma = [](double strain) {
    return (40.0 + 0.2 * std::sin(2 * kPi * strain / 0.013)) * kDegree;
  };
  AsymptoteDetector detector(kCriterion);
  Feed(detector, series, 0, 2 * kWindowSamples, kSpacing);
  const AsymptoteDetector::Result result = detector.Evaluate();
  EXPECT_TRUE(result.detected);
  EXPECT_NEAR(result.psi_sigma / kDegree, 40.0, 0.05);
  EXPECT_NEAR(result.slope_lnp, 1.2, 1e-9);
}

TEST(AsymptoteDetector, ConstantMeanStressIsDetected) {
  // Isochoric asymptotic state: p, e and ψ_σ stay constant.
  AsymptoteDetector detector(kCriterion);
  Feed(detector, Series{}, 0, 2 * kWindowSamples, kSpacing);
  const AsymptoteDetector::Result result = detector.Evaluate();
  EXPECT_TRUE(result.detected);
  EXPECT_EQ(result.slope_lnp, 0.0);
  EXPECT_EQ(result.lnp_half_difference, 0.0);
  // With no spread in ln p the volume slope is reported as 0, not NaN.
  EXPECT_EQ(result.slope_lnv_lnp, 0.0);
  EXPECT_NEAR(result.psi_sigma, 35.0 * kDegree, 1e-15);
}

TEST(AsymptoteDetector, PsiDriftAboveTheToleranceIsNotDetected) {
  for (const double change_deg : {0.8, -0.8, 0.3, -0.3}) {
    Series series = ParallelToALine(2.0, 0.05);
    const double rate = change_deg / kCriterion.window_strain;  // degrees per unit strain
    series.psi_sigma = [rate](double strain) { return (30.0 + rate * strain) * kDegree; };
    AsymptoteDetector detector(kCriterion);
    Feed(detector, series, 0, 2 * kWindowSamples, kSpacing);
    const AsymptoteDetector::Result result = detector.Evaluate();
    EXPECT_NEAR(result.psi_change_deg, std::abs(change_deg), 1e-9) << change_deg;
    EXPECT_EQ(result.detected, std::abs(change_deg) < kCriterion.psi_tolerance_deg) << change_deg;
    EXPECT_NEAR(result.lnp_half_difference, 0.0, 1e-9);
  }
}

TEST(AsymptoteDetector, LnPCurvatureBeyondTheToleranceIsNotDetected) {
  // ln p = ln p0 + a ε + c ε²: d ln p/dε changes by 2c per unit strain. With
  // 51 samples per window the halves hold 25 and 26 equally spaced samples
  // whose mean strains are 0.051 apart; the least-squares slope of a
  // quadratic is its derivative at the mean strain, so
  //   |Δln p (2nd half) − Δln p (1st half)| = 2|c| 0.051 × window/2.
  for (const double curvature : {6.0, -6.0, 2.0, -2.0}) {
    Series series = ParallelToALine(1.0, 0.04);
    series.log_p = [curvature](double strain) {
      return std::log(50.0) + 1.0 * strain + curvature * strain * strain;
    };
    AsymptoteDetector detector(kCriterion);
    Feed(detector, series, 0, 2 * kWindowSamples, kSpacing);
    const AsymptoteDetector::Result result = detector.Evaluate();
    const double expected = 2 * std::abs(curvature) * 0.051 * 0.5 * kCriterion.window_strain;
    EXPECT_NEAR(result.lnp_half_difference, expected, 1e-9) << curvature;
    EXPECT_EQ(result.detected, expected < kCriterion.lnp_tolerance) << curvature;
    EXPECT_NEAR(result.psi_change_deg, 0.0, 1e-9);
    // The overall slope is the derivative at the window's mean strain 0.15.
    EXPECT_NEAR(result.slope_lnp, 1.0 + 2 * curvature * 0.15, 1e-9) << curvature;
  }
}

TEST(AsymptoteDetector, ToleranceBoundariesAreStrict) {
  // "below psi_tolerance_deg" and "differ by less than lnp_tolerance": a
  // measured value equal to its tolerance is not an asymptotic state, the
  // next larger tolerance admits it.
  Series series = ParallelToALine(1.0, 0.04);
  series.psi_sigma = [](double strain) { return (30.0 + 3.0 * strain) * kDegree; };
  series.log_p = [](double strain) { return 0.5 * strain + 1.5 * strain * strain; };
  AsymptoteDetector probe(kCriterion);
  Feed(probe, series, 0, 2 * kWindowSamples, kSpacing);
  const AsymptoteDetector::Result measured = probe.Evaluate();
  ASSERT_GT(measured.psi_change_deg, 0.0);
  ASSERT_GT(measured.lnp_half_difference, 0.0);
  const double inf = std::numeric_limits<double>::infinity();
  auto detected_with = [&](double psi_tolerance_deg, double lnp_tolerance) {
    AsymptoteCriterion criterion = kCriterion;
    criterion.psi_tolerance_deg = psi_tolerance_deg;
    criterion.lnp_tolerance = lnp_tolerance;
    AsymptoteDetector detector(criterion);
    detector.set_samples(probe.samples());
    return detector.Evaluate().detected;
  };
  const double psi_at = measured.psi_change_deg, lnp_at = measured.lnp_half_difference;
  const double psi_above = std::nextafter(psi_at, inf), lnp_above = std::nextafter(lnp_at, inf);
  EXPECT_FALSE(detected_with(psi_at, lnp_above));
  EXPECT_FALSE(detected_with(psi_above, lnp_at));
  EXPECT_FALSE(detected_with(psi_at, lnp_at));
  EXPECT_TRUE(detected_with(psi_above, lnp_above));
}

TEST(AsymptoteDetector, OnlyTheLastWindowIsEvaluated) {
  // A transient (ψ_σ at 20°, ln p curved) up to ε = 0.099, then the
  // stationary state (ψ_σ at 30°, ln p linear): the transient samples still
  // kept in the record do not count once a full window lies beyond them.
  const double transient_end = 0.099;
  const Series line = ParallelToALine(2.0, 0.05);
  Series series = line;
  series.psi_sigma = [transient_end](double strain) {
    return (strain < transient_end ? 20.0 : 30.0) * kDegree;
  };
  series.log_p = [line, transient_end](double strain) {
    const double before = std::min(strain - transient_end, 0.0);
    return line.log_p(strain) + 30.0 * before * before;
  };
  AsymptoteDetector detector(kCriterion);
  Feed(detector, series, 0, 2 * kWindowSamples, kSpacing);  // the record spans 0.05 .. 0.2
  ASSERT_LT(detector.samples().front().strain, transient_end);
  const AsymptoteDetector::Result result = detector.Evaluate();
  EXPECT_TRUE(result.detected);
  EXPECT_NEAR(result.psi_sigma / kDegree, 30.0, 1e-12);
  EXPECT_NEAR(result.psi_change_deg, 0.0, 1e-12);
  EXPECT_NEAR(result.slope_lnp, 2.0, 1e-9);
  // One sample earlier the window starts with the last transient sample.
  AsymptoteDetector earlier(kCriterion);
  Feed(earlier, series, 0, 2 * kWindowSamples - 1, kSpacing);
  const AsymptoteDetector::Result early = earlier.Evaluate();
  EXPECT_FALSE(early.detected);
  EXPECT_GT(early.psi_change_deg, kCriterion.psi_tolerance_deg);
}

TEST(AsymptoteDetector, NotReadyBeforeAFullWindow) {
  AsymptoteDetector detector(kCriterion);
  const Series series = ParallelToALine(1.0, 0.05);
  for (int k = 0; k < kWindowSamples; ++k) {
    detector.Add(At(series, k * kSpacing));
    EXPECT_FALSE(detector.ready()) << k;
    EXPECT_FALSE(detector.Evaluate().detected) << k;
  }
  detector.Add(At(series, kWindowSamples * kSpacing));
  EXPECT_TRUE(detector.ready());
  EXPECT_TRUE(detector.Evaluate().detected);
}

TEST(AsymptoteDetector, NotReadyWithFewerThanEightSamples) {
  // Sparse samples (window/5 apart) span a full window after six samples.
  AsymptoteCriterion criterion = kCriterion;
  criterion.sample_strain = criterion.window_strain / 5;
  AsymptoteDetector detector(criterion);
  const Series series = ParallelToALine(1.0, 0.05);
  for (int k = 0; k < 7; ++k) {
    detector.Add(At(series, k * criterion.sample_strain));
    EXPECT_FALSE(detector.ready()) << k;
  }
  ASSERT_GE(detector.samples().back().strain - detector.samples().front().strain,
            criterion.window_strain);
  detector.Add(At(series, 7 * criterion.sample_strain));
  EXPECT_TRUE(detector.ready());
  EXPECT_TRUE(detector.Evaluate().detected);
}

TEST(AsymptoteDetector, HalfWindowWithFewerThanThreeSamplesIsNotDetected) {
  // Eight samples spanning the window, but the second half holds only one.
  AsymptoteDetector detector(kCriterion);
  const Series series;
  for (int k = 0; k < 7; ++k) detector.Add(At(series, 0.005 * k));
  detector.Add(At(series, kCriterion.window_strain));
  ASSERT_TRUE(detector.ready());
  EXPECT_FALSE(detector.Evaluate().detected);
}

TEST(AsymptoteDetector, NonFiniteLogPRestartsTheRecord) {
  const Series series = ParallelToALine(1.5, 0.05);
  for (const double bad : {std::nan(""), -std::numeric_limits<double>::infinity(),
                           std::numeric_limits<double>::infinity()}) {
    AsymptoteDetector detector(kCriterion);
    Feed(detector, series, 0, 2 * kWindowSamples, kSpacing);
    ASSERT_TRUE(detector.Evaluate().detected);
    // p <= 0 (no contacts) gives ln p = −inf or NaN.
    Sample lost = At(series, (2 * kWindowSamples + 1) * kSpacing);
    lost.log_p = bad;
    detector.Add(lost);
    EXPECT_TRUE(detector.samples().empty()) << bad;
    EXPECT_FALSE(detector.ready()) << bad;
    EXPECT_FALSE(detector.Evaluate().detected) << bad;
    // The record restarts: a full new window is needed.
    const int restart = 2 * kWindowSamples + 2;
    Feed(detector, series, restart, restart + kWindowSamples - 1, kSpacing);
    EXPECT_FALSE(detector.ready()) << bad;
    detector.Add(At(series, (restart + kWindowSamples) * kSpacing));
    EXPECT_TRUE(detector.ready()) << bad;
    EXPECT_TRUE(detector.Evaluate().detected) << bad;
  }
}

TEST(AsymptoteDetector, KeepsAboutOneAndAHalfWindows) {
  AsymptoteDetector detector(kCriterion);
  const Series series = ParallelToALine(1.0, 0.05);
  const double keep = 1.5 * kCriterion.window_strain;
  for (int k = 0; k <= 20 * kWindowSamples; ++k) {
    detector.Add(At(series, k * kSpacing));
    const double span = detector.samples().back().strain - detector.samples().front().strain;
    ASSERT_LE(span, keep) << k;
    if (k * kSpacing > keep + kSpacing) {
      ASSERT_GT(span, keep - kSpacing * (1 + 1e-9)) << k;
    }
    ASSERT_EQ(detector.samples().back().strain, k * kSpacing);
  }
  EXPECT_LE(detector.samples().size(), size_t{76});
  EXPECT_GE(detector.samples().size(), size_t{75});
  detector.Reset();
  EXPECT_TRUE(detector.samples().empty());
  EXPECT_FALSE(detector.ready());
}

}  // namespace
}  // namespace granasym::dem
