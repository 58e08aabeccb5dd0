#include "dem/engine.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dem/contact_statistics.h"
#include "dem/packing.h"

namespace granasym::dem {
namespace {

Material Elastic(double friction_angle = 0.0) {
  Material material;
  material.youngs_modulus = 500e6;
  material.stiffness_ratio = 0.3;
  material.friction_angle = friction_angle;
  material.density = 2650.0;
  material.local_damping = 0.0;
  return material;
}

Packing TwoSpheres(std::array<double, 3> a, std::array<double, 3> b, double radius,
                   double side = 0.02) {
  Packing packing;
  packing.cell = {side, side, side};
  packing.positions = {a, b};
  packing.radii = {radius, radius};
  return packing;
}

Engine::Options StepOptions(double dt, int threads = 1) {
  Engine::Options options;
  options.time_step = dt;
  options.threads = threads;
  return options;
}

// Index in the engine of the sphere with input index `id`.
size_t Slot(const Engine& engine, int64_t id) {
  for (size_t k = 0; k < engine.size(); ++k) {
    if (engine.ids()[k] == id) return k;
  }
  return engine.size();
}

TEST(EngineOptions, DefaultOptionsAreValid) {
  std::string why;
  EXPECT_TRUE(Engine::Options{}.IsValid(&why)) << why;
  EXPECT_TRUE(Material{}.IsValid(&why)) << why;
}

TEST(Engine, TwoSphereNormalImpactIsElasticWithTheAnalyticContactDuration) {
  const double r = 0.5e-3, speed = 0.05;
  const Material material = Elastic(0.5);  // friction present, but the impact is head-on
  const double mass = material.density * 4.0 / 3.0 * kPi * r * r * r;
  const double omega = std::sqrt(material.youngs_modulus * r / (0.5 * mass));
  const double contact_duration = kPi / omega;
  const double dt = contact_duration / 2000.0;
  Engine engine(TwoSpheres({0.008, 0.01, 0.01}, {0.008 + 2 * r + 2e-6, 0.01, 0.01}, r), material,
                StepOptions(dt));
  engine.SetVelocity(Slot(engine, 0), {speed, 0, 0});
  engine.SetVelocity(Slot(engine, 1), {-speed, 0, 0});
  const double energy_before = KineticEnergy(engine);
  int contact_steps = 0;
  bool touched = false;
  for (int step = 0; step < 200000; ++step) {
    engine.Step({true, false});
    if (engine.sums().contacts > 0) {
      ++contact_steps;
      touched = true;
    } else if (touched) {
      break;
    }
  }
  ASSERT_TRUE(touched);
  EXPECT_NEAR(contact_steps * dt, contact_duration, 2.0 * dt);
  const double energy_after = KineticEnergy(engine);
  EXPECT_NEAR(energy_after / energy_before, 1.0, 1e-6);
  const double restitution = -engine.velocities()[Slot(engine, 0)].x / speed;
  EXPECT_NEAR(restitution, 1.0, 1e-6);
}

TEST(ContactLaw, SlidingIsCappedAtTheCoulombLimitAgainstTheMotion) {
  const double mu = std::tan(0.5);
  LinearCundallStrack law({500e6, 0.3, mu}, 1e-7);
  const double r = 0.5e-3, overlap = 1e-6;
  LinearCundallStrack::Pair pair;
  pair.branch = {2 * r - overlap, 0, 0};
  pair.distance = 2 * r - overlap;
  pair.radius_i = pair.radius_j = r;
  pair.centre_velocity = {0, 1.0, 0};  // j slides along +y
  Vec3 shear{};
  // One small increment: elastic, F_s = k_s Δu_s on i along +y.
  LinearCundallStrack::Result result = law.Evaluate<true>(pair, {shear});
  shear = result.shear;
  const double k_n = law.NormalStiffness(r, r);
  EXPECT_NEAR(shear.y, 0.3 * k_n * 1.0 * 1e-7, 1e-18);
  // Keep sliding until the cap: |F_s| = μ F_n, along the motion of j (drags i).
  for (int k = 0; k < 2000; ++k) {
    result = law.Evaluate<true>(pair, {shear});
    shear = result.shear;
  }
  EXPECT_NEAR(Norm(shear), mu * k_n * overlap, 1e-12 * mu * k_n * overlap);
  EXPECT_GT(shear.y, 0.0);
  EXPECT_NEAR(shear.x, 0.0, 1e-20);
  // Torque on i: (r − u/2) n × F_s.
  EXPECT_NEAR(result.torque_i.z, (r - 0.5 * overlap) * shear.y, 1e-18);
}

TEST(ContactLaw, VectorisedBatchAgreesWithTheScalarEvaluator) {
  LinearCundallStrack law({500e6, 0.3, std::tan(0.5)}, 1.2e-7);
  SplitMix64 random(5);
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * random.Uniform(); };
  LinearCundallStrack::Batch batch;
  std::vector<LinearCundallStrack::Pair> pairs;
  std::vector<Vec3> shears;
  const int count = 100;
  for (int k = 0; k < count; ++k) {
    LinearCundallStrack::Pair pair;
    pair.radius_i = uniform(0.1e-3, 0.5e-3);
    pair.radius_j = uniform(0.1e-3, 0.5e-3);
    const Vec3 direction = {uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
    pair.distance = (pair.radius_i + pair.radius_j) * uniform(0.95, 0.9999);
    pair.branch = (pair.distance / Norm(direction)) * direction;
    pair.centre_velocity = {uniform(-0.1, 0.1), uniform(-0.1, 0.1), uniform(-0.1, 0.1)};
    pair.spin_i = {uniform(-50, 50), uniform(-50, 50), uniform(-50, 50)};
    pair.spin_j = {uniform(-50, 50), uniform(-50, 50), uniform(-50, 50)};
    // Half of the stored forces far above the Coulomb limit (sliding).
    const double size = k % 2 ? 1e-4 : 10.0;
    const Vec3 shear = {uniform(-size, size), uniform(-size, size), uniform(-size, size)};
    pairs.push_back(pair);
    shears.push_back(shear);
    batch.bx[k] = pair.branch.x;
    batch.by[k] = pair.branch.y;
    batch.bz[k] = pair.branch.z;
    batch.d2[k] = Dot(pair.branch, pair.branch);
    batch.ri[k] = pair.radius_i;
    batch.rj[k] = pair.radius_j;
    batch.vx[k] = pair.centre_velocity.x;
    batch.vy[k] = pair.centre_velocity.y;
    batch.vz[k] = pair.centre_velocity.z;
    batch.wix[k] = pair.spin_i.x;
    batch.wiy[k] = pair.spin_i.y;
    batch.wiz[k] = pair.spin_i.z;
    batch.wjx[k] = pair.spin_j.x;
    batch.wjy[k] = pair.spin_j.y;
    batch.wjz[k] = pair.spin_j.z;
    batch.sx[k] = shear.x;
    batch.sy[k] = shear.y;
    batch.sz[k] = shear.z;
  }
  law.EvaluateBatch<true>(batch, count);
  int sliding = 0;
  for (int k = 0; k < count; ++k) {
    const LinearCundallStrack::Result r = law.Evaluate<true>(pairs[k], {shears[k]});
    const double scale = Norm(r.force_i);
    EXPECT_NEAR(batch.fx[k], r.force_i.x, 1e-12 * scale) << k;
    EXPECT_NEAR(batch.fy[k], r.force_i.y, 1e-12 * scale) << k;
    EXPECT_NEAR(batch.fz[k], r.force_i.z, 1e-12 * scale) << k;
    EXPECT_NEAR(batch.sx[k], r.shear.x, 1e-12 * scale) << k;
    EXPECT_NEAR(batch.tix[k], r.torque_i.x, 1e-12 * scale * pairs[k].radius_i) << k;
    EXPECT_NEAR(batch.tjz[k], r.torque_j.z, 1e-12 * scale * pairs[k].radius_j) << k;
    sliding += Norm(r.shear) < Norm(shears[k]);
  }
  EXPECT_GT(sliding, 20);  // the cap was exercised
}

TEST(ContactLaw, RigidRotationOfThePairKeepsTheShearForceMagnitude) {
  LinearCundallStrack law({500e6, 0.3, 10.0}, 1e-6);
  const double r = 0.5e-3, overlap = 1e-6, d = 2 * r - overlap;
  // Rigid rotation about z at rate w: centres move perpendicular to l, both
  // spheres spin at w, so the contact point has no relative slip.
  const double w = 100.0;
  Vec3 shear{0, 1e-3, 0};
  double angle = 0.0;
  Vec3 n{};
  for (int k = 0; k < 1000; ++k) {
    LinearCundallStrack::Pair pair;
    n = {std::cos(angle), std::sin(angle), 0};
    pair.branch = d * n;
    pair.distance = d;
    pair.radius_i = pair.radius_j = r;
    pair.centre_velocity = (w * d) * Vec3{-n.y, n.x, 0};
    pair.spin_i = pair.spin_j = {0, 0, w};
    shear = law.Evaluate<true>(pair, {shear}).shear;
    angle += w * 1e-6;
  }
  // The force turned with the pair (0.1 rad) and kept its magnitude.
  EXPECT_NEAR(Norm(shear), 1e-3, 2e-6);
  EXPECT_NEAR(Dot(shear, n), 0.0, 1e-15);
  EXPECT_NEAR(shear.x, -1e-3 * std::sin(angle - w * 1e-6), 1e-6);
}

// Forces on two overlapping spheres placed at `a` and `a + offset`.
std::array<Vec3, 2> PairForces(std::array<double, 3> a, std::array<double, 3> offset) {
  std::array<double, 3> b = {a[0] + offset[0], a[1] + offset[1], a[2] + offset[2]};
  const double side = 0.01;
  for (double& x : b) x -= side * std::floor(x / side);
  Engine engine(TwoSpheres(a, b, 0.5e-3, side), Elastic(0.5), StepOptions(1e-8));
  engine.SetVelocity(Slot(engine, 1), {0.01, -0.02, 0.03});
  engine.Step({true, false});
  engine.ComputeForces({true, false});
  const auto& f = engine.forces();
  return {Xyz(f[Slot(engine, 0)]), Xyz(f[Slot(engine, 1)])};
}

TEST(Engine, ContactAcrossEachFaceAndCornerEqualsTheSameContactInside) {
  const std::array<double, 3> offset = {0.6e-3, 0.5e-3, 0.4e-3};  // |offset| < 2r: overlapping
  const auto inside = PairForces({0.004, 0.004, 0.004}, offset);
  ASSERT_GT(Norm(inside[0]), 0.0);
  const std::array<std::array<double, 3>, 4> placements = {{{0.0098, 0.004, 0.004},
                                                            {0.004, 0.0098, 0.004},
                                                            {0.004, 0.004, 0.0098},
                                                            {0.0098, 0.0098, 0.0098}}};
  for (const auto& a : placements) {
    const auto across = PairForces(a, offset);
    for (int k = 0; k < 2; ++k) {
      EXPECT_NEAR(across[k].x, inside[k].x, 1e-9 * Norm(inside[0]));
      EXPECT_NEAR(across[k].y, inside[k].y, 1e-9 * Norm(inside[0]));
      EXPECT_NEAR(across[k].z, inside[k].z, 1e-9 * Norm(inside[0]));
    }
  }
}

TEST(Engine, ASecondEvaluationAtTheSamePositionsDoesNotSlideTheContactsAgain) {
  const double r = 0.5e-3;
  Engine engine(TwoSpheres({0.004, 0.004, 0.004}, {0.004 + 0.95e-3, 0.0042, 0.004}, r, 0.01),
                Elastic(0.5), StepOptions(1e-8));
  engine.SetVelocity(Slot(engine, 1), {0.0, 0.05, 0.01});
  engine.SetSpin(Slot(engine, 0), {0.0, 0.0, 30.0});
  for (int step = 0; step < 20; ++step) engine.Step();
  engine.ComputeForces({false, false});
  const std::vector<Vec4> first = engine.forces();
  engine.ComputeForces({true, true});
  const std::vector<Vec4> second = engine.forces();
  // Equal up to rounding (the first evaluation runs the vectorised batch,
  // the second the scalar evaluator); sliding again would change the shear
  // force by k_s Δt |v_t|, a twentieth of it after these 20 steps.
  for (size_t i = 0; i < first.size(); ++i) {
    const double scale = Norm(Xyz(first[i]));
    EXPECT_NEAR(first[i].x, second[i].x, 1e-13 * scale);
    EXPECT_NEAR(first[i].y, second[i].y, 1e-13 * scale);
    EXPECT_NEAR(first[i].z, second[i].z, 1e-13 * scale);
  }
  EXPECT_NE(first[0].y, 0.0);  // the contact carries a shear force
  EXPECT_EQ(engine.sums().contacts, 1);
}

TEST(Engine, LoveWeberStressOfOneNormalContact) {
  const double r = 0.5e-3, overlap = 2e-6, side = 0.01;
  Engine engine(TwoSpheres({0.004, 0.005, 0.005}, {0.004 + 2 * r - overlap, 0.005, 0.005}, r, side),
                Elastic(0.5), StepOptions(1e-8));
  engine.ComputeForces({true, false});
  const double k_n = 500e6 * r;
  const double expected = k_n * overlap * (2 * r - overlap) / (side * side * side);
  EXPECT_NEAR(engine.sums().stress[0], expected, 1e-9 * expected);
  for (int k = 1; k < 6; ++k) EXPECT_NEAR(engine.sums().stress[k], 0.0, 1e-12 * expected);
  EXPECT_EQ(engine.sums().contacts, 1);
  // Compression positive: the stress of a repulsive contact is positive.
  EXPECT_GT(engine.sums().stress[0], 0.0);
}

TEST(Engine, AffineStretchingOfAContactFreeGasProducesNoForce) {
  Packing packing;
  packing.cell = {0.01, 0.01, 0.01};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      for (int k = 0; k < 4; ++k) {
        packing.positions.push_back({0.0025 * i + 0.001, 0.0025 * j + 0.001, 0.0025 * k + 0.001});
        packing.radii.push_back(0.4e-3);
      }
    }
  }
  Material material = Elastic(0.5);
  material.local_damping = 0.5;
  Engine engine(packing, material, StepOptions(1e-7));
  const std::vector<Vec4> before = engine.scaled_positions();
  engine.SetVelocityGradient({50.0, -30.0, 20.0});
  for (int step = 0; step < 1000; ++step) engine.Step({true, false});
  EXPECT_EQ(engine.sums().contacts, 0);
  for (size_t i = 0; i < engine.size(); ++i) {
    EXPECT_EQ(Norm(Xyz(engine.forces()[i])), 0.0);
    EXPECT_EQ(Norm(Xyz(engine.velocities()[i])), 0.0);
    // Scaled positions are unchanged: the particles moved affinely.
    EXPECT_DOUBLE_EQ(engine.scaled_positions()[i].x, before[i].x);
  }
  EXPECT_NEAR(engine.cell()[0], 0.01 * std::exp(50.0 * 1e-7 * 1000), 1e-15);
}

}  // namespace
}  // namespace granasym::dem
