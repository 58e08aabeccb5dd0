// The adaptive time step against closed forms: the shortest contact duration
// of two spheres pressed together (Hertz: π sqrt(m_12/(2E* sqrt(R* u_N)))),
// its bound by the impact duration, the largest Δt, and the schedule.
#include "dem/adaptive_time_step.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/state_measures.h"
#include "dem/engine.h"
#include "dem/material.h"
#include "two_spheres.h"

namespace granasym::dem {
namespace {

using testing::StepOptions;
using testing::TwoSpheres;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

Material Hertz() {
  Material material;
  material.contact_law = ContactLaw::kHertzMindlin;
  material.poissons_ratio = 0.25;
  return material;
}

// Two spheres of radii r_i, r_j whose centres are r_i + r_j − overlap apart,
// with their forces evaluated (the list then holds the pair).
Engine Pressed(const Material& material, double r_i, double r_j, double overlap) {
  const double x = 0.004;
  Engine engine(
      TwoSpheres({x, 0.005, 0.005}, {x + r_i + r_j - overlap, 0.005, 0.005}, r_i, r_j, 0.01),
      material, StepOptions(1e-8));
  engine.ComputeForces({false, false});
  return engine;
}

// π sqrt(m_12/k_n) with the Hertz tangent stiffness k_n = 2E* sqrt(R* u_N),
// written from SPEC §8.1 (not from the law's code).
double HertzDuration(const Material& m, double r_i, double r_j, double overlap) {
  const double e_star = m.youngs_modulus / (2 * (1 - m.poissons_ratio * m.poissons_ratio));
  const double reduced_radius = r_i * r_j / (r_i + r_j);
  const double k_n = 2 * e_star * std::sqrt(reduced_radius * overlap);
  const double m_i = SphereMass(r_i, m.density), m_j = SphereMass(r_j, m.density);
  return kPi * std::sqrt(m_i * m_j / (m_i + m_j) / k_n);
}

TEST(AdaptiveTimeStep, DefaultOptionsAreValid) {
  std::string why;
  EXPECT_TRUE(AdaptiveTimeStep::Options{}.IsValid(&why)) << why;
  AdaptiveTimeStep::Options bad;
  bad.check_interval = 0;
  EXPECT_FALSE(bad.IsValid(&why));
  EXPECT_NE(why.find("check_interval"), std::string::npos) << why;
  bad = {};
  bad.fraction = 0;
  EXPECT_FALSE(bad.IsValid(&why));
  EXPECT_NE(why.find("fraction"), std::string::npos) << why;
}

TEST(AdaptiveTimeStep, TheDurationOfTwoHertzSpheresPressedTogetherIsTheAnalyticOne) {
  const Material material = Hertz();
  const double r_i = 0.1e-3, r_j = 0.25e-3;
  double previous = kInfinity;
  for (double relative : {1e-4, 1e-3, 4e-3, 1.6e-2, 6.4e-2}) {
    const double overlap = relative * (r_i + r_j);
    const double duration = Pressed(material, r_i, r_j, overlap).SmallestContactDuration();
    EXPECT_NEAR(duration, HertzDuration(material, r_i, r_j, overlap), 1e-9 * duration)
        << "relative overlap " << relative;
    // It shrinks as the overlap grows, as u_N^(-1/4): by sqrt(2) for 4 times the overlap.
    if (std::isfinite(previous)) {
      EXPECT_LT(duration, previous);
      if (relative > 1e-3) {
        EXPECT_NEAR(previous / duration, std::sqrt(2.0), 1e-6);
      }
    }
    previous = duration;
  }
}

TEST(AdaptiveTimeStep, ALinearContactLastsAsLongAtEveryOverlap) {
  const Material material;  // the paper's linear law
  const double r_i = 0.1e-3, r_j = 0.4e-3;
  const double m_i = SphereMass(r_i, material.density), m_j = SphereMass(r_j, material.density);
  const double k_n = 2 * material.youngs_modulus * r_i * r_j / (r_i + r_j);
  const double expected = kPi * std::sqrt(m_i * m_j / (m_i + m_j) / k_n);
  for (double relative : {1e-4, 1e-2, 5e-2}) {
    const double duration =
        Pressed(material, r_i, r_j, relative * (r_i + r_j)).SmallestContactDuration();
    EXPECT_NEAR(duration, expected, 1e-12 * expected);
  }
  // Unequal spheres last longer than the two smaller ones would (the bound
  // of the rule holds for every linear pair).
  const ContactDurations durations = ComputeContactDurations({r_i, r_j}, material);
  EXPECT_GT(expected, durations.smallest_reduced_mass);
  // So the rule is f t_impact whatever the contacts: exactly, without a pass.
  const AdaptiveTimeStep rule(AdaptiveTimeStep::Options{}, material, {r_i, r_j});
  EXPECT_EQ(rule.Evaluate(Pressed(material, r_i, r_i, 0.05 * 2 * r_i)), rule.UpperBound());
  EXPECT_EQ(rule.UpperBound(), 0.1 * durations.smallest_reduced_mass);
}

TEST(AdaptiveTimeStep, WithoutAContactTheDurationIsInfiniteAndTheStepTheImpactBound) {
  const Material material = Hertz();
  const double r = 0.1e-3;
  Engine apart(TwoSpheres({0.004, 0.005, 0.005}, {0.0045, 0.005, 0.005}, r, r, 0.01), material,
               StepOptions(1e-8));
  apart.ComputeForces({false, false});
  EXPECT_EQ(apart.SmallestContactDuration(), kInfinity);
  const ContactDurations durations = ComputeContactDurations({r, r}, material);
  AdaptiveTimeStep::Options options;
  options.fraction = 0.2;
  const AdaptiveTimeStep rule(options, material, {r, r});
  EXPECT_EQ(rule.impact_duration(), durations.smallest_reduced_mass);
  EXPECT_EQ(rule.Evaluate(apart), 0.2 * durations.smallest_reduced_mass);
  EXPECT_EQ(rule.UpperBound(), 0.2 * durations.smallest_reduced_mass);
}

TEST(AdaptiveTimeStep, FollowsTheHertzDurationOnceItIsShorterThanAnImpactAtOneMetrePerSecond) {
  const Material material = Hertz();
  const double r = 0.1e-3;  // two equal spheres: the impact bound is their own
  const ContactDurations durations = ComputeContactDurations({r, r}, material);
  AdaptiveTimeStep::Options options;
  options.fraction = 0.1;
  const AdaptiveTimeStep rule(options, material, {r, r});
  // A slight overlap is softer than an impact at 1 m/s: the bound holds.
  const Engine slight = Pressed(material, r, r, 1e-4 * 2 * r);
  ASSERT_GT(slight.SmallestContactDuration(), durations.smallest_reduced_mass);
  EXPECT_EQ(rule.Evaluate(slight), 0.1 * durations.smallest_reduced_mass);
  // Deeper overlaps (u_N/(r_i + r_j) of 1 % to 8 %): Δt = f · the analytic
  // duration, shrinking as the overlap grows.
  double previous = rule.UpperBound();
  for (double relative : {0.01, 0.02, 0.04, 0.08}) {
    const double overlap = relative * 2 * r;
    const double expected = 0.1 * HertzDuration(material, r, r, overlap);
    ASSERT_LT(expected, rule.UpperBound()) << relative;
    const double dt = rule.Evaluate(Pressed(material, r, r, overlap));
    EXPECT_NEAR(dt, expected, 1e-9 * expected) << relative;
    EXPECT_LT(dt, previous);
    previous = dt;
  }
  // Δt_max caps it.
  options.max_time_step = 0.5 * previous;
  EXPECT_EQ(
      AdaptiveTimeStep(options, material, {r, r}).Evaluate(Pressed(material, r, r, 0.02 * 2 * r)),
      0.5 * previous);
  EXPECT_EQ(AdaptiveTimeStep(options, material, {r, r}).UpperBound(), 0.5 * previous);
}

TEST(AdaptiveTimeStep, AHeldSphereCountsWithItsPartnersMassOnly) {
  // m_12 = 1/(1/m_i + 1/m_j) from the inverse masses: a held sphere (1/m = 0)
  // leaves m_12 = m_j; two held spheres have no duration.
  const Material material = Hertz();
  const double r = 0.1e-3, overlap = 0.01 * 2 * r;
  Engine engine = Pressed(material, r, r, overlap);
  const double both = engine.SmallestContactDuration();
  engine.SetInverseMassAndInertia(testing::Slot(engine, 0), 0.0, 0.0);
  EXPECT_NEAR(engine.SmallestContactDuration(), std::sqrt(2.0) * both, 1e-12 * both);
  engine.SetInverseMassAndInertia(testing::Slot(engine, 1), 0.0, 0.0);
  EXPECT_EQ(engine.SmallestContactDuration(), kInfinity);
}

TEST(AdaptiveTimeStep, IsEvaluatedAtEachStageStartAndEveryCheckInterval) {
  AdaptiveTimeStep::Options options;
  options.check_interval = 25;
  const AdaptiveTimeStep rule(options, Material{}, {1e-4});
  EXPECT_TRUE(rule.Due(0));
  EXPECT_FALSE(rule.Due(1));
  EXPECT_FALSE(rule.Due(24));
  EXPECT_TRUE(rule.Due(25));
  EXPECT_TRUE(rule.Due(250));
  EXPECT_NE(rule.Describe().find("every 25 steps"), std::string::npos) << rule.Describe();
}

}  // namespace
}  // namespace granasym::dem
