// The asymptotic-state detectors of dem/asymptote_detector.h, one per kind of
// path, on synthetic series with a known asymptote and on series that still
// drift, against the criteria stated in AsymptoteCriterion.
#include "dem/asymptote_detector.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <vector>

#include "common/error.h"
#include "common/state_measures.h"
#include "dem/scene.h"
#include "dem/stage_validity.h"
#include "test_util.h"

namespace granasym::dem {
namespace {

using Sample = AsymptoteDetector::Sample;
using Curve = std::function<double(double)>;  // a state measure as a function of strain

// A synthetic series: state measures as functions of the accumulated strain.
// The cell strains follow a strain path of direction psi_epsilon.
struct Series {
  Curve psi_sigma = [](double) { return 35.0 * kDegree; };
  Curve log_p = [](double) { return std::log(100.0); };
  Curve log_volume = [](double) { return std::log(1.6); };
  Curve psi_epsilon = [](double) { return 90.0 * kDegree; };
};

// Integrates the strain increments of the series' ψ_ε up to `strain` with
// the midpoint rule over steps of `spacing` (exact for a constant ψ_ε).
void CellStrains(const Series& series, double strain, double spacing, double* eps_a,
                 double* eps_r) {
  *eps_a = *eps_r = 0;
  const int steps = static_cast<int>(std::lround(strain / spacing));
  for (int k = 0; k < steps; ++k) {
    const AxisymmetricRate rate =
        AxisymmetricRate::FromAngle(series.psi_epsilon((k + 0.5) * spacing), 1.0);
    *eps_a += rate.axial * spacing;
    *eps_r += rate.radial * spacing;
  }
}

Sample At(const Series& series, double strain, double spacing) {
  Sample s{strain, series.psi_sigma(strain), series.log_p(strain), series.log_volume(strain)};
  CellStrains(series, strain, spacing, &s.eps_a, &s.eps_r);
  s.time = strain;  // any increasing clock
  return s;
}

// Adds samples k = first .. last (inclusive) at strain k * spacing.
void Feed(AsymptoteDetector& detector, const Series& series, int first, int last, double spacing) {
  for (int k = first; k <= last; ++k) detector.Add(At(series, k * spacing, spacing));
}

AsymptoteCriterion Criterion(PathKind kind) { return AsymptoteCriterion::For(kind); }

// A state moving parallel to an asymptotic line: ln p = ln p0 + a ε and
// ln(1 + e) = ln(1 + e0) − λ* (ln p − ln p0), along ψ_ε.
Series ParallelToALine(double slope_lnp, double lambda_star, double psi_epsilon_deg) {
  Series series;
  series.log_p = [slope_lnp](double strain) { return std::log(80.0) + slope_lnp * strain; };
  series.log_volume = [slope_lnp, lambda_star](double strain) {
    return std::log(1.7) - lambda_star * slope_lnp * strain;
  };
  series.psi_epsilon = [psi_epsilon_deg](double) { return psi_epsilon_deg * kDegree; };
  series.psi_sigma = [](double) { return 14.0 * kDegree; };
  return series;
}

TEST(AsymptoteDetector, DefaultCriteriaAreTheDocumentedOnes) {
  const AsymptoteCriterion isochoric = Criterion(PathKind::kIsochoric);
  EXPECT_EQ(isochoric.sample_strain, 5e-4);
  EXPECT_EQ(isochoric.window_strain, 0.15);
  EXPECT_EQ(isochoric.psi_tolerance_deg, 1.0);
  EXPECT_EQ(isochoric.lnp_tolerance, 0.05);
  for (const PathKind kind : {PathKind::kCompression, PathKind::kExtension}) {
    const AsymptoteCriterion c = Criterion(kind);
    EXPECT_EQ(c.kind, kind);
    EXPECT_EQ(c.window_lnp, 1.0);
    EXPECT_EQ(c.window_strain, 0.3);
    // Extension: twice the standard error of ψ_σ's fitted change measured
    // along the paper's extension paths (the criterion's comment).
    EXPECT_EQ(c.psi_tolerance_deg, kind == PathKind::kExtension ? 2.0 : 1.0);
    EXPECT_EQ(c.slope_tolerance, 0.1);
  }
  EXPECT_EQ(Criterion(PathKind::kExtension).floor_kpa, 0.5);
  EXPECT_NE(Criterion(PathKind::kExtension).Describe().find("p >= 0.5 kPa"), std::string::npos);
  EXPECT_EQ(Criterion(PathKind::kCompression).Describe().find("p >="), std::string::npos);
  const AsymptoteCriterion stress = Criterion(PathKind::kStressControlled);
  EXPECT_EQ(stress.window_strain, 0.15);
  EXPECT_EQ(stress.psi_tolerance_deg, 1.0);
  EXPECT_EQ(stress.psi_epsilon_tolerance_deg, 3.0);
  EXPECT_EQ(stress.lnv_tolerance, 0.004);
  // Each description names its kind and its tolerances.
  EXPECT_NE(Criterion(PathKind::kCompression).Describe().find("ln p"), std::string::npos);
  EXPECT_NE(stress.Describe().find("stress_controlled"), std::string::npos);
  EXPECT_NE(stress.Describe().find("0.004"), std::string::npos);
}

TEST(AsymptoteDetector, StrainPathKindFollowsPsiEpsilon) {
  EXPECT_EQ(StrainPathKind(90.0), PathKind::kIsochoric);
  EXPECT_EQ(StrainPathKind(-90.0), PathKind::kIsochoric);
  EXPECT_EQ(StrainPathKind(90.0 + 5e-7), PathKind::kIsochoric);
  EXPECT_EQ(StrainPathKind(90.0 - 2e-6), PathKind::kCompression);
  EXPECT_EQ(StrainPathKind(0.0), PathKind::kCompression);
  EXPECT_EQ(StrainPathKind(-45.0), PathKind::kCompression);
  EXPECT_EQ(StrainPathKind(90.0 + 2e-6), PathKind::kExtension);
  EXPECT_EQ(StrainPathKind(120.0), PathKind::kExtension);
  EXPECT_EQ(StrainPathKind(-180.0), PathKind::kExtension);
  EXPECT_EQ(ToString(PathKind::kStressControlled), std::string("stress_controlled"));
  EXPECT_EQ(FromString<AsymptoteStatus>("not_reached"), AsymptoteStatus::kNotReached);
}

// --- isochoric ---

TEST(IsochoricDetector, ConstantMeanStressAndPsiSigmaIsDetected) {
  const AsymptoteCriterion c = Criterion(PathKind::kIsochoric);
  AsymptoteDetector detector(c);
  const double h = c.sample_strain;
  Feed(detector, Series{}, 0, 400, h);
  const AsymptoteDetector::Result result = detector.Evaluate();
  EXPECT_EQ(result.status, AsymptoteStatus::kDetected);
  EXPECT_NEAR(result.window_strain, c.window_strain, h);
  EXPECT_NEAR(result.mean_stress_kpa, 100.0, 1e-9);
  EXPECT_NEAR(result.void_ratio, 0.6, 1e-12);
  EXPECT_NEAR(result.psi_sigma, 35.0 * kDegree, 1e-12);
  EXPECT_NEAR(result.psi_epsilon / kDegree, 90.0, 1e-9);
  EXPECT_NEAR(result.q_over_p, 3.0 / std::sqrt(2.0) * std::tan(35.0 * kDegree), 1e-12);
  EXPECT_EQ(result.lnp_change, 0.0);
}

TEST(IsochoricDetector, NoisyStationaryStateIsDetected) {
  // A 3000-sphere critical state: ±15 % in p and ±0.8° in ψ_σ, no trend.
  Series series;
  series.log_p = [](double strain) {
    return std::log(30.0) + 0.15 * std::sin(2 * kPi * strain / 0.013);
  };
  series.psi_sigma = [](double strain) {
    return (27.5 + 0.8 * std::sin(2 * kPi * strain / 0.017)) * kDegree;
  };
  const AsymptoteCriterion c = Criterion(PathKind::kIsochoric);
  AsymptoteDetector detector(c);
  Feed(detector, series, 0, 600, c.sample_strain);
  EXPECT_TRUE(detector.Evaluate().detected());
}

TEST(IsochoricDetector, FallingMeanStressIsDrifting) {
  // p still falls towards the critical state: 0.6 of ln p per unit strain
  // is 0.09 across the window, above lnp_tolerance = 0.05; 0.2 is 0.03.
  for (const double rate : {-0.6, -0.2}) {
    Series series;
    series.log_p = [rate](double strain) { return std::log(200.0) + rate * strain; };
    const AsymptoteCriterion c = Criterion(PathKind::kIsochoric);
    AsymptoteDetector detector(c);
    Feed(detector, series, 0, 400, c.sample_strain);
    const AsymptoteDetector::Result result = detector.Evaluate();
    EXPECT_NEAR(result.lnp_change, std::abs(rate) * result.window_strain, 1e-9);
    EXPECT_EQ(result.status, std::abs(rate) * c.window_strain < c.lnp_tolerance
                                 ? AsymptoteStatus::kDetected
                                 : AsymptoteStatus::kDrifting)
        << rate;
  }
}

TEST(IsochoricDetector, PsiSigmaDriftAboveTheToleranceIsDrifting) {
  for (const double change_deg : {1.5, -1.5, 0.6, -0.6}) {
    const AsymptoteCriterion c = Criterion(PathKind::kIsochoric);
    Series series;
    const double rate = change_deg / c.window_strain;
    series.psi_sigma = [rate](double strain) { return (30.0 + rate * strain) * kDegree; };
    AsymptoteDetector detector(c);
    Feed(detector, series, 0, 400, c.sample_strain);
    const AsymptoteDetector::Result result = detector.Evaluate();
    EXPECT_NEAR(result.psi_change_deg, std::abs(change_deg), 1e-6) << change_deg;
    EXPECT_EQ(result.detected(), std::abs(change_deg) < c.psi_tolerance_deg) << change_deg;
  }
}

TEST(IsochoricDetector, ToleranceBoundariesAreStrict) {
  Series series;
  series.psi_sigma = [](double strain) { return (30.0 + 3.0 * strain) * kDegree; };
  series.log_p = [](double strain) { return 0.2 * strain; };
  AsymptoteDetector probe(Criterion(PathKind::kIsochoric));
  Feed(probe, series, 0, 400, probe.criterion().sample_strain);
  const AsymptoteDetector::Result measured = probe.Evaluate();
  ASSERT_GT(measured.psi_change_deg, 0.0);
  ASSERT_GT(measured.lnp_change, 0.0);
  const double inf = std::numeric_limits<double>::infinity();
  auto detected_with = [&](double psi_tolerance_deg, double lnp_tolerance) {
    AsymptoteCriterion criterion = probe.criterion();
    criterion.psi_tolerance_deg = psi_tolerance_deg;
    criterion.lnp_tolerance = lnp_tolerance;
    AsymptoteDetector detector(criterion);
    detector.set_samples(probe.samples());
    return detector.Evaluate().detected();
  };
  const double psi_at = measured.psi_change_deg, lnp_at = measured.lnp_change;
  const double psi_above = std::nextafter(psi_at, inf), lnp_above = std::nextafter(lnp_at, inf);
  EXPECT_FALSE(detected_with(psi_at, lnp_above));
  EXPECT_FALSE(detected_with(psi_above, lnp_at));
  EXPECT_TRUE(detected_with(psi_above, lnp_above));
}

TEST(IsochoricDetector, AGasAtOneKpaMeetsTheCriterionButIsAGas) {
  // The state the single-criterion detector accepted: 0.8 kPa, e = 1.01,
  // stationary. The criterion holds; the validity guard calls it a gas
  // (mechanical coordination 2: particles touch in chains, no network).
  Series series;
  series.log_p = [](double) { return std::log(0.8); };
  series.log_volume = [](double) { return std::log(2.01); };
  const AsymptoteCriterion c = Criterion(PathKind::kIsochoric);
  AsymptoteDetector detector(c);
  Feed(detector, series, 0, 400, c.sample_strain);
  const AsymptoteDetector::Result result = detector.Evaluate();
  EXPECT_TRUE(result.detected());
  EXPECT_NEAR(result.mean_stress_kpa, 0.8, 1e-12);
  EXPECT_TRUE(IsGas(result.mean_stress_kpa, 2.0));
  EXPECT_FALSE(IsGas(result.mean_stress_kpa, 3.5));  // 0.8 kPa is above the floor
  EXPECT_TRUE(IsGas(0.4, 4.5));                      // below the floor of 0.5 kPa
  EXPECT_FALSE(IsGas(30.0, 3.4));                    // the critical state of 3000 spheres
  EXPECT_TRUE(IsGas(std::nan(""), 4.0));
}

// --- compression and extension ---

TEST(CompressionDetector, StateMovingParallelToAnNclIsDetectedOverAWindowInLnP) {
  // 50 of ln p per unit strain (λ* = 0.024 at ψ_ε = 45°): the window of
  // 1.0 in ln p is 0.02 of strain, far shorter than a strain window.
  const AsymptoteCriterion c = Criterion(PathKind::kCompression);
  AsymptoteDetector detector(c);
  const Series series = ParallelToALine(50.0, 0.024, 45.0);
  Feed(detector, series, 0, 80, c.sample_strain);
  const AsymptoteDetector::Result result = detector.Evaluate();
  EXPECT_EQ(result.status, AsymptoteStatus::kDetected);
  EXPECT_GE(result.window_lnp, c.window_lnp);
  EXPECT_LT(result.window_lnp, c.window_lnp + 50.0 * c.sample_strain + 1e-9);
  EXPECT_NEAR(result.window_strain, 0.02, c.sample_strain);
  EXPECT_NEAR(result.slope_lnv_lnp, -0.024, 1e-9);
  EXPECT_NEAR(result.slope_change, 0.0, 1e-6);
  EXPECT_NEAR(result.psi_epsilon / kDegree, 45.0, 1e-9);
  // p at the window: the mean of p over it, between its ends.
  EXPECT_GT(result.mean_stress_kpa, std::exp(series.log_p(0.04 - result.window_strain)));
  EXPECT_LT(result.mean_stress_kpa, std::exp(series.log_p(0.04)));
}

TEST(CompressionDetector, SlowPathsUseTheStrainWindow) {
  // ψ_ε near 90°: 2 of ln p per unit strain never spans 1.0 of ln p within
  // the longest window of 0.3.
  const AsymptoteCriterion c = Criterion(PathKind::kCompression);
  AsymptoteDetector detector(c);
  Feed(detector, ParallelToALine(2.0, 0.03, 85.0), 0, 1000, c.sample_strain);
  const AsymptoteDetector::Result result = detector.Evaluate();
  EXPECT_TRUE(result.detected());
  EXPECT_NEAR(result.window_strain, c.window_strain, c.sample_strain);
  EXPECT_NEAR(result.window_lnp, 0.6, 2.0 * c.sample_strain);
}

TEST(CompressionDetector, ASlopeThatStillChangesIsDrifting) {
  // ln p = 50 ε − b ε²: d ln(1+e)/d ln p = −50 λ/(50 − 2bε) still changes.
  // At ε = 0.06, b = 300 leaves d ln p/dε = 14 (a window of 0.07 of strain
  // over which it changes by about half its mean); b = 10 leaves 48.8 and a
  // change of 0.4 % across the window of 0.02.
  for (const double curvature : {300.0, 10.0}) {
    Series series = ParallelToALine(50.0, 0.024, 45.0);
    series.log_p = [curvature](double strain) {
      return std::log(80.0) + 50.0 * strain - curvature * strain * strain;
    };
    const AsymptoteCriterion c = Criterion(PathKind::kCompression);
    AsymptoteDetector detector(c);
    Feed(detector, series, 0, 120, c.sample_strain);
    const AsymptoteDetector::Result result = detector.Evaluate();
    ASSERT_NE(result.status, AsymptoteStatus::kNotReached);
    EXPECT_EQ(result.detected(), curvature < 100) << curvature << " " << result.slope_change;
    if (curvature > 100) {
      EXPECT_GT(result.slope_change, 0.3);
    }
  }
}

TEST(CompressionDetector, PsiSigmaStillRisingIsDrifting) {
  // ψ_σ rising by 2° per unit ln p: 2° across the window (tolerance 0.5°).
  Series series = ParallelToALine(50.0, 0.024, 45.0);
  series.psi_sigma = [](double strain) { return (5.0 + 2.0 * 50.0 * strain) * kDegree; };
  AsymptoteDetector detector(Criterion(PathKind::kCompression));
  Feed(detector, series, 0, 100, detector.criterion().sample_strain);
  const AsymptoteDetector::Result result = detector.Evaluate();
  EXPECT_EQ(result.status, AsymptoteStatus::kDrifting);
  EXPECT_NEAR(result.psi_change_deg, 2.0 * result.window_lnp, 0.05);
}

TEST(CompressionDetector, TheAsymptoteIsFoundOneWindowAfterTheTransient) {
  // ψ_σ rises to 12° until ln p has grown by 2 (0.04 of strain), then stays:
  // the first detection comes one window of ln p after the transient.
  Series series = ParallelToALine(50.0, 0.024, 45.0);
  series.psi_sigma = [](double strain) {
    return (strain < 0.04 ? 2.0 + 250.0 * strain : 12.0) * kDegree;
  };
  const AsymptoteCriterion c = Criterion(PathKind::kCompression);
  AsymptoteDetector detector(c);
  double first = -1;
  for (int k = 0; k <= 200 && first < 0; ++k) {
    detector.Add(At(series, k * c.sample_strain, c.sample_strain));
    if (detector.Evaluate().detected()) first = k * c.sample_strain;
  }
  ASSERT_GT(first, 0);
  // One window (0.02) after the transient, within the tolerance's reach.
  EXPECT_GT(first, 0.04 + 0.01);
  EXPECT_LT(first, 0.04 + 0.025);
  EXPECT_NEAR(detector.Evaluate().psi_sigma / kDegree, 12.0, 0.3);
}

TEST(ExtensionDetector, FallingMeanStressParallelToALineIsDetected) {
  const AsymptoteCriterion c = Criterion(PathKind::kExtension);
  AsymptoteDetector detector(c);
  // ψ_ε = 120°: volume grows while p falls (d ln(1+e)/d ln p < 0).
  Feed(detector, ParallelToALine(-20.0, 0.04, 120.0), 0, 200, c.sample_strain);
  const AsymptoteDetector::Result result = detector.Evaluate();
  EXPECT_TRUE(result.detected());
  EXPECT_GE(result.window_lnp, c.window_lnp);  // |Δ ln p| of a falling p
  EXPECT_NEAR(result.window_strain, 0.05, c.sample_strain);
  EXPECT_NEAR(result.slope_lnp, -20.0, 1e-9);
  EXPECT_NEAR(result.psi_epsilon / kDegree, 120.0, 1e-9);
}

// An elastic start: a proportional stress path (ψ_σ steady) whose ln p falls
// by the whole window within 0.05 of strain is detected at once, unless the
// criterion's transient_strain keeps windows out until the path has strained.
TEST(ExtensionDetector, NoWindowCountsWithinTheTransientStrain) {
  AsymptoteCriterion c = Criterion(PathKind::kExtension);
  AsymptoteDetector plain(c);
  Feed(plain, ParallelToALine(-20.0, 0.04, 120.0), 0, 100, c.sample_strain);
  EXPECT_TRUE(plain.Evaluate().detected());
  c.transient_strain = 0.1;
  AsymptoteDetector late(c);
  Feed(late, ParallelToALine(-20.0, 0.04, 120.0), 0, 100, c.sample_strain);  // up to 0.05
  EXPECT_FALSE(late.ready());
  EXPECT_FALSE(late.Evaluate().detected());
  Feed(late, ParallelToALine(-20.0, 0.04, 120.0), 101, 320, c.sample_strain);  // up to 0.16
  EXPECT_TRUE(late.Evaluate().detected());
  EXPECT_NE(c.Describe().find("no window before 0.1 of accumulated strain"), std::string::npos);
}

// A proportional path towards the origin (SPEC §8.4): from p0 = 50 kPa, ln p
// falls by `rate` per unit strain and ln(1+e) rises along a line of slope
// −0.05 in ln(1+e)–ln p, while ψ_σ stays at 40° with Gaussian noise of
// `noise_deg` (a fixed seed) — until strain `collapse`, where the network
// is lost: p falls a hundredfold within 0.01 of strain and ψ_σ then wanders
// by ±10°.
Series TowardsTheOrigin(double rate, double noise_deg, double collapse) {
  auto noise = std::make_shared<std::vector<double>>();
  std::mt19937 generator(7);
  std::normal_distribution<double> normal(0.0, noise_deg);
  for (int k = 0; k < 20000; ++k) noise->push_back(normal(generator));
  Series series;
  series.psi_epsilon = [](double) { return 100.0 * kDegree; };
  series.log_p = [rate, collapse](double strain) {
    const double lnp = std::log(50.0) - rate * strain;
    return strain <= collapse ? lnp
                              : lnp - std::log(100.0) * std::min(1.0, (strain - collapse) / 0.01);
  };
  series.log_volume = [rate](double strain) { return std::log(1.7) + 0.05 * rate * strain; };
  series.psi_sigma = [noise, collapse](double strain) {
    const size_t k = static_cast<size_t>(std::lround(strain / 5e-4)) % noise->size();
    const double wander = strain > collapse ? 10.0 * std::sin(40.0 * strain) : 0.0;
    return (40.0 + (*noise)[k] + wander) * kDegree;
  };
  return series;
}

// Feeds samples 0 .. last with Track after each, as a run does.
void FeedTracked(AsymptoteDetector& detector, const Series& series, int last) {
  const double spacing = detector.criterion().sample_strain;
  for (int k = 0; k <= last; ++k) {
    detector.Add(At(series, k * spacing, spacing));
    detector.Track();
  }
}

TEST(ExtensionDetector, ANoisyPathTowardsTheOriginIsDetectedAboveTheFloor) {
  // ln p falls by 8 per unit strain: from 50 kPa to the floor (0.5 kPa) at
  // strain 0.58, on to 0.1 kPa at 0.78 (no collapse).
  const Series series = TowardsTheOrigin(8.0, 1.5, 10.0);
  AsymptoteDetector detector(Criterion(PathKind::kExtension));
  FeedTracked(detector, series, 1560);
  // The last window reaches below the floor: it is not evaluated.
  const AsymptoteDetector::Result end = detector.Evaluate();
  EXPECT_TRUE(end.below_floor);
  EXPECT_FALSE(end.detected());
  EXPECT_LT(end.p_min_kpa, 0.5);
  // The last window that held lies wholly above the floor and ends where p
  // reached it; its state is the path's.
  ASSERT_TRUE(detector.last_held().has_value());
  const AsymptoteDetector::Result& held = *detector.last_held();
  EXPECT_TRUE(held.detected());
  EXPECT_GE(held.p_min_kpa, 0.5);
  EXPECT_LT(held.p_min_kpa, 0.5 * std::exp(8.0 * 5e-4 * 1.01));
  EXPECT_NEAR(held.p_max_kpa / held.p_min_kpa, std::exp(1.0), 0.05);  // one window of ln p
  EXPECT_NEAR(held.window_end_strain, std::log(100.0) / 8.0, 1e-3);
  EXPECT_NEAR(held.psi_sigma / kDegree, 40.0, 0.5);
  EXPECT_NEAR(held.slope_lnv_lnp, -0.05, 1e-9);
  EXPECT_NEAR(held.psi_epsilon / kDegree, 100.0, 1e-9);
}

TEST(ExtensionDetector, APathThatNeverSettlesHoldsNoWindow) {
  Series series = TowardsTheOrigin(8.0, 0.0, 10.0);
  // ψ_σ still rising by 10° per 0.1 of strain all the way down.
  series.psi_sigma = [](double strain) { return (20.0 + 100.0 * strain) * kDegree; };
  AsymptoteDetector detector(Criterion(PathKind::kExtension));
  FeedTracked(detector, series, 1560);
  EXPECT_FALSE(detector.last_held().has_value());
  EXPECT_FALSE(detector.Evaluate().detected());
}

TEST(ExtensionDetector, APathThatSettlesAndThenLosesItsNetworkKeepsItsState) {
  // Proportional to strain 0.4 (p = 2 kPa), then collapsing to 0.02 kPa and
  // wandering; further on a stationary stretch below the floor, which must
  // not replace the state.
  Series series = TowardsTheOrigin(8.0, 1.0, 0.4);
  AsymptoteDetector detector(Criterion(PathKind::kExtension));
  FeedTracked(detector, series, 800);
  ASSERT_TRUE(detector.last_held().has_value());
  const AsymptoteDetector::Result held = *detector.last_held();
  EXPECT_LE(held.window_end_strain, 0.4 + 1e-9);
  EXPECT_GE(held.p_min_kpa, 50.0 * std::exp(-8.0 * 0.4) * 0.999);
  EXPECT_NEAR(held.psi_sigma / kDegree, 40.0, 0.5);
  series.psi_sigma = [](double) { return 40.0 * kDegree; };
  series.log_p = [](double strain) { return std::log(0.02) - 2.0 * (strain - 0.4); };
  for (int k = 801; k <= 2000; ++k) {
    detector.Add(At(series, k * 5e-4, 5e-4));
    detector.Track();
  }
  ASSERT_TRUE(detector.last_held().has_value());
  EXPECT_EQ(detector.last_held()->window_end_strain, held.window_end_strain);
  EXPECT_TRUE(detector.Evaluate().below_floor);
}

// The dense flow of an extension path at the paper's rate: p stays near
// 2 kPa (ln p scattering by 0.17 with a lag-one autocorrelation of 0.75,
// as measured) while ln(1+e) rises and ψ_σ stays at 40°. The relative change
// of d ln(1+e)/d ln p divides by a rate of ln p near zero; the change of the
// rate of ln p does not, and the state is found.
TEST(ExtensionDetector, ADenseFlowAtNearlyConstantPressureIsDetected) {
  auto noise = std::make_shared<std::vector<double>>();
  std::mt19937 generator(11);
  std::normal_distribution<double> normal(0.0, 0.17 * std::sqrt(1 - 0.75 * 0.75));
  double previous = 0;
  for (int k = 0; k < 4000; ++k) {
    // AR(1) per output row of 0.002 strain (4 samples), held between rows.
    if (k % 4 == 0) previous = 0.75 * previous + normal(generator);
    noise->push_back(previous);
  }
  Series series;
  series.psi_epsilon = [](double) { return 100.0 * kDegree; };
  series.log_p = [noise](double strain) {
    const size_t k = static_cast<size_t>(std::lround(strain / 5e-4)) % noise->size();
    return std::log(2.0) + (*noise)[k];
  };
  series.log_volume = [](double strain) { return std::log(1.7) + 0.3 * strain; };
  series.psi_sigma = [](double) { return 40.0 * kDegree; };
  AsymptoteDetector detector(Criterion(PathKind::kExtension));
  FeedTracked(detector, series, 1200);
  const AsymptoteDetector::Result end = detector.Evaluate();
  EXPECT_FALSE(end.below_floor);
  EXPECT_TRUE(end.detected()) << end.lnp_half_difference;
  EXPECT_LT(end.lnp_half_difference, 0.4);
  EXPECT_NEAR(end.mean_stress_kpa, 2.0, 0.3);
  // The same path whose pressure stops falling halfway through the window
  // (0.3 to 0.6 of strain; ln p falling by 6 per unit strain, then level):
  // the rate of ln p changed by 6 × 0.15 = 0.9 of ln p over half a window,
  // and no state is found there although ψ_σ is stationary.
  Series bend = series;
  bend.log_p = [](double strain) { return std::log(20.0) - 6.0 * std::min(strain, 0.45); };
  AsymptoteDetector bent(Criterion(PathKind::kExtension));
  FeedTracked(bent, bend, 1200);
  const AsymptoteDetector::Result at_bend = bent.Evaluate();
  EXPECT_NEAR(at_bend.lnp_half_difference, 0.9, 0.05);
  EXPECT_LT(at_bend.psi_change_deg, 0.1);
  EXPECT_FALSE(at_bend.detected());
}

TEST(ExtensionDetector, AWindowPacksIntoNumbersAndBack) {
  AsymptoteDetector detector(Criterion(PathKind::kExtension));
  FeedTracked(detector, TowardsTheOrigin(8.0, 1.0, 10.0), 700);
  ASSERT_TRUE(detector.last_held().has_value());
  const AsymptoteDetector::Result& held = *detector.last_held();
  const AsymptoteDetector::Result back = UnpackResult(PackResult(held));
  EXPECT_EQ(PackResult(back), PackResult(held));
  EXPECT_EQ(back.status, held.status);
  EXPECT_EQ(back.p_min_kpa, held.p_min_kpa);
  std::vector<double> short_one = PackResult(held);
  short_one.pop_back();
  EXPECT_THROW(UnpackResult(short_one), std::invalid_argument);
  std::vector<double> bad_status = PackResult(held);
  bad_status[0] = 9;
  EXPECT_THROW(UnpackResult(bad_status), std::invalid_argument);
}

// --- stress-controlled ---

// A drained triaxial test: ψ_ε(ε) from dilation (ψ_ε > 90°) towards 90°.
Series Triaxial(double dilation_deg, double decay_strain) {
  Series series;
  series.psi_epsilon = [dilation_deg, decay_strain](double strain) {
    return (90.0 + dilation_deg * std::exp(-strain / decay_strain)) * kDegree;
  };
  series.psi_sigma = [](double) { return 22.5 * kDegree; };
  series.log_p = [](double) { return std::log(283.0); };
  return series;
}

void AddVolume(Series& series, double spacing) {
  // ln(1+e) follows the volumetric strain: d ln(1+e) = −dε_v.
  series.log_volume = [series, spacing](double strain) {
    double eps_a, eps_r;
    CellStrains(series, strain, spacing, &eps_a, &eps_r);
    return std::log(1.65) - (eps_a + 2 * eps_r);
  };
}

TEST(StressControlledDetector, ASteadyCriticalStateIsDetected) {
  const AsymptoteCriterion c = Criterion(PathKind::kStressControlled);
  Series series = Triaxial(0.0, 1.0);
  AddVolume(series, c.sample_strain);
  AsymptoteDetector detector(c);
  Feed(detector, series, 0, 400, c.sample_strain);
  const AsymptoteDetector::Result result = detector.Evaluate();
  EXPECT_TRUE(result.detected());
  EXPECT_NEAR(result.psi_epsilon / kDegree, 90.0, 1e-9);
  EXPECT_NEAR(result.lnv_change, 0.0, 1e-12);
  EXPECT_NEAR(result.mean_stress_kpa, 283.0, 1e-9);
}

TEST(StressControlledDetector, ASampleStillDilatingIsDrifting) {
  // ψ_ε = 90° + 10° exp(−ε/0.2): ψ_σ and p are steady, but the sample
  // still dilates (ln(1+e) grows by ~0.01 across the window, ψ_ε falls).
  const AsymptoteCriterion c = Criterion(PathKind::kStressControlled);
  Series series = Triaxial(10.0, 0.2);
  AddVolume(series, c.sample_strain);
  AsymptoteDetector detector(c);
  Feed(detector, series, 0, 600, c.sample_strain);  // to ε = 0.3
  const AsymptoteDetector::Result result = detector.Evaluate();
  EXPECT_EQ(result.status, AsymptoteStatus::kDrifting);
  EXPECT_GT(result.lnv_change, c.lnv_tolerance);
  EXPECT_GT(result.psi_epsilon / kDegree, 90.5);
  // Later the dilation has died out and the state is asymptotic.
  Feed(detector, series, 601, 3000, c.sample_strain);  // to ε = 1.5
  EXPECT_TRUE(detector.Evaluate().detected());
}

TEST(StressControlledDetector, PsiEpsilonOfTheHalvesIsComparedNotTheRates) {
  // A ψ_ε that alternates by ±20° every sample (noisy rates) but whose
  // increments over each half-window agree: detected.
  const AsymptoteCriterion c = Criterion(PathKind::kStressControlled);
  Series series = Triaxial(0.0, 1.0);
  const double h = c.sample_strain;
  series.psi_epsilon = [h](double strain) {
    const long k = std::lround(std::floor(strain / h));
    return (90.0 + (k % 2 == 0 ? 20.0 : -20.0)) * kDegree;
  };
  AddVolume(series, h);
  AsymptoteDetector detector(c);
  Feed(detector, series, 0, 400, h);
  const AsymptoteDetector::Result result = detector.Evaluate();
  EXPECT_LT(result.psi_epsilon_change_deg, c.psi_epsilon_tolerance_deg);
  EXPECT_NEAR(result.psi_epsilon / kDegree, 90.0, 0.5);
}

// --- the record ---

TEST(AsymptoteDetector, NotReachedBeforeAFullWindow) {
  const AsymptoteCriterion c = Criterion(PathKind::kIsochoric);
  AsymptoteDetector detector(c);
  const int window = static_cast<int>(std::lround(c.window_strain / c.sample_strain));
  for (int k = 0; k < window; ++k) {
    detector.Add(At(Series{}, k * c.sample_strain, c.sample_strain));
    ASSERT_FALSE(detector.ready()) << k;
    ASSERT_EQ(detector.Evaluate().status, AsymptoteStatus::kNotReached) << k;
  }
  detector.Add(At(Series{}, window * c.sample_strain, c.sample_strain));
  EXPECT_TRUE(detector.ready());
  EXPECT_TRUE(detector.Evaluate().detected());
}

TEST(AsymptoteDetector, NonFiniteLogPRestartsTheRecord) {
  const AsymptoteCriterion c = Criterion(PathKind::kIsochoric);
  for (const double bad : {std::nan(""), -std::numeric_limits<double>::infinity()}) {
    AsymptoteDetector detector(c);
    Feed(detector, Series{}, 0, 400, c.sample_strain);
    ASSERT_TRUE(detector.Evaluate().detected());
    Sample lost = At(Series{}, 401 * c.sample_strain, c.sample_strain);
    lost.log_p = bad;  // p <= 0 (no contacts)
    detector.Add(lost);
    EXPECT_TRUE(detector.samples().empty()) << bad;
    EXPECT_EQ(detector.Evaluate().status, AsymptoteStatus::kNotReached) << bad;
  }
}

TEST(AsymptoteDetector, KeepsAboutOneAndAHalfLongestWindows) {
  for (const PathKind kind : {PathKind::kIsochoric, PathKind::kCompression}) {
    const AsymptoteCriterion c = Criterion(kind);
    AsymptoteDetector detector(c);
    const double keep = 1.5 * c.window_strain;
    for (int k = 0; k <= 3000; ++k) {
      detector.Add(At(Series{}, k * c.sample_strain, c.sample_strain));
      const double span = detector.samples().back().strain - detector.samples().front().strain;
      ASSERT_LE(span, keep + 1e-12) << k;
    }
    EXPECT_NEAR(detector.samples().back().strain - detector.samples().front().strain, keep,
                c.sample_strain);
  }
}

std::string SceneError(const std::string& stage) {
  try {
    Scene::Parse(testing::SampleToml(500, 4.6, 1) + stage, "asymptote.toml", "");
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(AsymptoteCriterion, EachKindReadsItsOwnKeysOnly) {
  const std::string triaxial =
      "[[stage]]\ntype = 'triaxial'\naxial_strain_rate = 136.355\nradial_stress_kpa = 100.0\n"
      "[stage.stop]\nasymptote = true\nstrain_norm = 1.0\n[stage.asymptote]\n";
  EXPECT_EQ(SceneError(triaxial + "lnv_tolerance = 0.01\npsi_epsilon_tolerance_deg = 2.0\n"), "");
  EXPECT_NE(SceneError(triaxial + "window_lnp = 0.5\n").find("window_lnp"), std::string::npos);
  const std::string compression =
      "[[stage]]\npsi_epsilon_deg = 45.0\nstretching_rate = 167.0\n[stage.stop]\n"
      "asymptote = true\nstrain_norm = 0.3\n[stage.asymptote]\n";
  EXPECT_EQ(SceneError(compression + "window_lnp = 0.5\nslope_tolerance = 0.2\n"), "");
  EXPECT_NE(SceneError(compression + "lnp_tolerance = 0.5\n").find("lnp_tolerance"),
            std::string::npos);
  const std::string rest =
      "[[stage]]\ntype = 'rest'\nmean_stress_kpa = 100.0\n[stage.stop]\nasymptote = true\n";
  EXPECT_NE(SceneError(rest).find("no asymptote detector"), std::string::npos);
  // The kind's criterion is the stage's.
  const Scene scene = Scene::Parse(
      testing::SampleToml(500, 4.6, 1) + compression + "window_lnp = 0.5\n", "asymptote.toml", "");
  EXPECT_EQ(scene.stages[0].asymptote.kind, PathKind::kCompression);
  EXPECT_EQ(scene.stages[0].asymptote.window_lnp, 0.5);
  EXPECT_TRUE(scene.stages[0].detect_asymptote);
}

TEST(ExtensionDetector, TheFloorIsAKeyOfTheExtensionCriterionOnly) {
  const std::string extension =
      "[[stage]]\npsi_epsilon_deg = 100.0\nstretching_rate = 167.0\n[stage.stop]\n"
      "strain_norm = 1.0\n[stage.asymptote]\n";
  EXPECT_EQ(SceneError(extension + "floor_kpa = 2.0\n"), "");
  EXPECT_NE(SceneError(extension + "floor_kpa = -1.0\n").find("floor_kpa"), std::string::npos);
  const std::string compression =
      "[[stage]]\npsi_epsilon_deg = 45.0\nstretching_rate = 167.0\n[stage.stop]\n"
      "strain_norm = 1.0\n[stage.asymptote]\n";
  EXPECT_NE(SceneError(compression + "floor_kpa = 2.0\n").find("floor_kpa"), std::string::npos);
}

}  // namespace
}  // namespace granasym::dem
