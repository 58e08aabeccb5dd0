// The contact laws (linear_cundall_strack.h, hertz_mindlin.h,
// rolling_resistance.h): closed forms, caps, the vectorised batch against the
// scalar reference, and two-sphere runs of the engine.
#include "dem/contact_law.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iterator>
#include <vector>

#include "dem/contact_statistics.h"
#include "dem/engine.h"
#include "dem/hertz_mindlin.h"
#include "dem/linear_cundall_strack.h"
#include "dem/material.h"
#include "dem/packing.h"
#include "dem/rolling_resistance.h"
#include "two_spheres.h"

namespace granasym::dem {
namespace {

using testing::HeadOnImpact;
using testing::Impact;
using testing::Slot;
using testing::StepOptions;
using testing::TwoSpheres;

Material Elastic(ContactLaw law, double friction_angle = 0.5, double rolling_friction = 0.0) {
  Material material;
  material.contact_law = law;
  material.friction_angle = friction_angle;
  material.rolling_friction = rolling_friction;
  material.local_damping = 0.0;
  return material;
}

// Two spheres overlapping by `overlap` along x, at rest.
ContactPair StaticPair(double radius_i, double radius_j, double overlap) {
  ContactPair pair;
  pair.distance = radius_i + radius_j - overlap;
  pair.branch = {pair.distance, 0, 0};
  pair.radius_i = radius_i;
  pair.radius_j = radius_j;
  pair.centre_velocity = pair.spin_i = pair.spin_j = Vec3{};
  return pair;
}

// F_n and k_n of the material's normal law for a static pair.
NormalResponse NormalOf(const Material& material, double r_i, double r_j, double overlap) {
  const ContactPair pair = StaticPair(r_i, r_j, overlap);
  if (material.contact_law == ContactLaw::kLinear) {
    const LinearCundallStrack law(LinearCundallStrack::Params::FromMaterial(material), 1.0);
    return {law.Evaluate<false>(pair, {}).normal_force,
            law.NormalStiffness(r_i, r_j, pair.distance)};
  }
  const HertzMindlin law(HertzMindlin::Params::FromMaterial(material), 1.0);
  return {law.Evaluate<false>(pair, {}).normal_force, law.NormalStiffness(r_i, r_j, pair.distance)};
}

// ---------------------------------------------------------------------------
// Linear Cundall–Strack (the paper's law).

TEST(LinearCundallStrack, SlidingIsCappedAtTheCoulombLimitAgainstTheMotion) {
  const double mu = std::tan(0.5);
  LinearCundallStrack law({500e6, 0.3, mu}, 1e-7);
  const double r = 0.5e-3, overlap = 1e-6;
  ContactPair pair = StaticPair(r, r, overlap);
  pair.centre_velocity = {0, 1.0, 0};  // j slides along +y
  Vec3 shear{};
  // One small increment: elastic, F_s = k_s Δu_s on i along +y.
  ContactResult result = law.Evaluate<true>(pair, {shear});
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

TEST(LinearCundallStrack, RigidRotationOfThePairKeepsTheShearForceMagnitude) {
  LinearCundallStrack law({500e6, 0.3, 10.0}, 1e-6);
  const double r = 0.5e-3, overlap = 1e-6, d = 2 * r - overlap;
  // Rigid rotation about z at rate w: centres move perpendicular to l, both
  // spheres spin at w, so the contact point has no relative slip.
  const double w = 100.0;
  Vec3 shear{0, 1e-3, 0};
  double angle = 0.0;
  Vec3 n{};
  for (int k = 0; k < 1000; ++k) {
    ContactPair pair;
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

// ---------------------------------------------------------------------------
// The vectorised batch of every law against its scalar reference.

template <class Law>
Law MakeLaw(const Material& material, double time_step) {
  return Law(Law::Params::FromMaterial(material), time_step);
}

template <class Law>
class ContactLawBatch : public ::testing::Test {};
using Laws =
    ::testing::Types<LinearCundallStrack, HertzMindlin, RollingResistance<LinearCundallStrack>,
                     RollingResistance<HertzMindlin>>;
TYPED_TEST_SUITE(ContactLawBatch, Laws);

TYPED_TEST(ContactLawBatch, VectorisedBatchAgreesWithTheScalarEvaluator) {
  using Law = TypeParam;
  const ContactLaw kind =
      std::is_same_v<Law, HertzMindlin> || std::is_same_v<Law, RollingResistance<HertzMindlin>>
          ? ContactLaw::kHertzMindlin
          : ContactLaw::kLinear;
  const Law law = MakeLaw<Law>(Elastic(kind, 0.5, 0.3), 1.2e-7);
  SplitMix64 random(5);
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * random.Uniform(); };
  ContactBatch batch;
  std::vector<ContactPair> pairs;
  std::vector<ContactHistory> histories;
  const int count = 100;
  for (int k = 0; k < count; ++k) {
    ContactPair pair;
    pair.radius_i = uniform(0.1e-3, 0.5e-3);
    pair.radius_j = uniform(0.1e-3, 0.5e-3);
    const Vec3 direction = {uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
    pair.distance = (pair.radius_i + pair.radius_j) * uniform(0.95, 0.9999);
    pair.branch = (pair.distance / Norm(direction)) * direction;
    pair.centre_velocity = {uniform(-0.1, 0.1), uniform(-0.1, 0.1), uniform(-0.1, 0.1)};
    pair.spin_i = {uniform(-50, 50), uniform(-50, 50), uniform(-50, 50)};
    pair.spin_j = {uniform(-50, 50), uniform(-50, 50), uniform(-50, 50)};
    // Half of the stored forces and moments far above their caps (sliding,
    // rolling).
    const double size = k % 2 ? 1e-4 : 10.0;
    ContactHistory history;
    history.shear = {uniform(-size, size), uniform(-size, size), uniform(-size, size)};
    if constexpr (Law::kRollingHistory) {
      const double moment = size * 1e-4;
      history.rolling = {uniform(-moment, moment), uniform(-moment, moment),
                         uniform(-moment, moment)};
    }
    pairs.push_back(pair);
    histories.push_back(history);
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
    batch.sx[k] = history.shear.x;
    batch.sy[k] = history.shear.y;
    batch.sz[k] = history.shear.z;
    batch.rmx[k] = history.rolling.x;
    batch.rmy[k] = history.rolling.y;
    batch.rmz[k] = history.rolling.z;
  }
  law.template EvaluateBatch<true>(batch, count);
  int sliding = 0, rolling = 0;
  for (int k = 0; k < count; ++k) {
    const ContactResult r = law.template Evaluate<true>(pairs[k], histories[k]);
    const double scale = Norm(r.force_i);
    EXPECT_NEAR(batch.fx[k], r.force_i.x, 1e-12 * scale) << k;
    EXPECT_NEAR(batch.fy[k], r.force_i.y, 1e-12 * scale) << k;
    EXPECT_NEAR(batch.fz[k], r.force_i.z, 1e-12 * scale) << k;
    EXPECT_NEAR(batch.sx[k], r.shear.x, 1e-12 * scale) << k;
    EXPECT_NEAR(batch.sy[k], r.shear.y, 1e-12 * scale) << k;
    EXPECT_NEAR(batch.sz[k], r.shear.z, 1e-12 * scale) << k;
    const double torque = Norm(r.torque_i) + Norm(r.torque_j);
    EXPECT_NEAR(batch.tix[k], r.torque_i.x, 1e-12 * torque) << k;
    EXPECT_NEAR(batch.tiy[k], r.torque_i.y, 1e-12 * torque) << k;
    EXPECT_NEAR(batch.tiz[k], r.torque_i.z, 1e-12 * torque) << k;
    EXPECT_NEAR(batch.tjx[k], r.torque_j.x, 1e-12 * torque) << k;
    EXPECT_NEAR(batch.tjy[k], r.torque_j.y, 1e-12 * torque) << k;
    EXPECT_NEAR(batch.tjz[k], r.torque_j.z, 1e-12 * torque) << k;
    sliding += Norm(r.shear) < Norm(histories[k].shear);
    if constexpr (Law::kRollingHistory) {
      const double moment = Norm(r.rolling);
      ASSERT_GT(moment, 0.0);
      EXPECT_NEAR(batch.rmx[k], r.rolling.x, 1e-12 * moment) << k;
      EXPECT_NEAR(batch.rmy[k], r.rolling.y, 1e-12 * moment) << k;
      EXPECT_NEAR(batch.rmz[k], r.rolling.z, 1e-12 * moment) << k;
      rolling += moment < Norm(histories[k].rolling);
    }
  }
  EXPECT_GT(sliding, 20);  // the Coulomb cap was exercised
  if constexpr (Law::kRollingHistory) {
    EXPECT_GT(rolling, 20);  // and the rolling cap
  }
}

// The batch finishes the pairs below the Coulomb limit without the cap's
// square root and division and the others in a second loop (contact_law.h);
// it must give, bit for bit, what one loop with the cap on every pair gives:
// this reference, written out from the law's public pieces.
template <class Law>
void OneLoopBatch(const Law& law, ContactBatch& b, int count) {
  const double ratio = law.tangential_ratio(), mu = law.friction_coefficient();
  const double dt = law.time_step();
  for (int k = 0; k < count; ++k) {
    const LaneGeometry g = ContactGeometryLane(b, k);
    const NormalResponse response =
        law.Normal(b.ri[k], b.rj[k], g.distance, g.reciprocal, g.overlap);
    const double normal_force = response.force;
    double fx = -normal_force * g.nx, fy = -normal_force * g.ny, fz = -normal_force * g.nz;
    const double arm_i = b.ri[k] - 0.5 * g.overlap, arm_j = b.rj[k] - 0.5 * g.overlap;
    double rx, ry, rz;
    ContactRotationLane(b, k, g.nx, g.ny, g.nz, g.inverse_distance, dt, rx, ry, rz);
    double sx = b.sx[k], sy = b.sy[k], sz = b.sz[k];
    CarryWithContactLane(rx, ry, rz, g.nx, g.ny, g.nz, sx, sy, sz);
    const double ax = arm_i * b.wix[k] + arm_j * b.wjx[k];
    const double ay = arm_i * b.wiy[k] + arm_j * b.wjy[k];
    const double az = arm_i * b.wiz[k] + arm_j * b.wjz[k];
    const double cx = b.vx[k] - (ay * g.nz - az * g.ny);
    const double cy = b.vy[k] - (az * g.nx - ax * g.nz);
    const double cz = b.vz[k] - (ax * g.ny - ay * g.nx);
    const double cn = cx * g.nx + cy * g.ny + cz * g.nz;
    const double k_t_dt = ratio * response.stiffness * dt;
    sx += k_t_dt * (cx - cn * g.nx);
    sy += k_t_dt * (cy - cn * g.ny);
    sz += k_t_dt * (cz - cn * g.nz);
    CapLane(mu * normal_force, sx, sy, sz);
    b.sx[k] = sx;
    b.sy[k] = sy;
    b.sz[k] = sz;
    fx += sx;
    fy += sy;
    fz += sz;
    const double mx = g.ny * sz - g.nz * sy, my = g.nz * sx - g.nx * sz, mz = g.nx * sy - g.ny * sx;
    b.tix[k] = arm_i * mx;
    b.tiy[k] = arm_i * my;
    b.tiz[k] = arm_i * mz;
    b.tjx[k] = arm_j * mx;
    b.tjy[k] = arm_j * my;
    b.tjz[k] = arm_j * mz;
    b.fx[k] = fx;
    b.fy[k] = fy;
    b.fz[k] = fz;
  }
}

template <class Law>
class ShearLawBatch : public ::testing::Test {};
using ShearLaws = ::testing::Types<LinearCundallStrack, HertzMindlin>;
TYPED_TEST_SUITE(ShearLawBatch, ShearLaws);

TYPED_TEST(ShearLawBatch, SkippingTheCapBelowTheLimitIsBitIdenticalToOneLoop) {
  using Law = TypeParam;
  const ContactLaw kind =
      std::is_same_v<Law, HertzMindlin> ? ContactLaw::kHertzMindlin : ContactLaw::kLinear;
  const Law law = MakeLaw<Law>(Elastic(kind, 0.5), 1.2e-7);
  const Law frictionless_cap = MakeLaw<Law>(Elastic(kind, 1.5), 1.2e-7);
  SplitMix64 random(11);
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * random.Uniform(); };
  ContactBatch batch, reference;
  const int count = ContactBatch::kSize;
  // The shear force after the step scales with the stored one (it is carried
  // linearly, plus an increment): stored forces of a lane are scaled so that
  // the updated |F_s| lands within a few ulps of μ F_n, and elsewhere far
  // below, just below, far above, zero, and at a zero increment.
  const double kRelative[] = {0.0, 1e-3,      0.5,       1 - 1e-6,  1 - 1e-12, 1 - 1e-15, 1 - 2e-16,
                              1.0, 1 + 2e-16, 1 + 1e-15, 1 + 1e-12, 1 + 1e-6,  2.0,       1e3};
  int near_limit = 0;
  for (int k = 0; k < count; ++k) {
    const double ri = uniform(0.1e-3, 0.5e-3), rj = uniform(0.1e-3, 0.5e-3);
    const Vec3 direction = {uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
    const double distance = (ri + rj) * uniform(0.95, 0.9999);
    const Vec3 branch = (distance / Norm(direction)) * direction;
    batch.bx[k] = branch.x;
    batch.by[k] = branch.y;
    batch.bz[k] = branch.z;
    batch.d2[k] = Dot(branch, branch);
    batch.ri[k] = ri;
    batch.rj[k] = rj;
    const bool still = k % 7 == 0;  // no motion: the updated force is the stored one turned
    const double v = still ? 0.0 : 0.01, w = still ? 0.0 : 5.0;
    batch.vx[k] = uniform(-v, v);
    batch.vy[k] = uniform(-v, v);
    batch.vz[k] = uniform(-v, v);
    batch.wix[k] = uniform(-w, w);
    batch.wiy[k] = uniform(-w, w);
    batch.wiz[k] = uniform(-w, w);
    batch.wjx[k] = uniform(-w, w);
    batch.wjy[k] = uniform(-w, w);
    batch.wjz[k] = uniform(-w, w);
    // A tangential stored force of unit size, then scaled by bisection of
    // the updated |F_s| (measured with a cap that never acts) onto the target.
    const Vec3 n = (1.0 / Norm(branch)) * branch;
    Vec3 t = Cross(n, Vec3{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)});
    t = (1.0 / Norm(t)) * t;
    const LaneGeometry g = ContactGeometryLane(batch, k);
    const double limit =
        law.friction_coefficient() * law.Normal(ri, rj, g.distance, g.reciprocal, g.overlap).force;
    const double target = limit * kRelative[k % std::size(kRelative)];
    auto updated = [&](double size) {
      ContactBatch probe = batch;
      probe.sx[k] = size * t.x;
      probe.sy[k] = size * t.y;
      probe.sz[k] = size * t.z;
      OneLoopBatch(frictionless_cap, probe, k + 1);
      return std::sqrt(probe.sx[k] * probe.sx[k] + probe.sy[k] * probe.sy[k] +
                       probe.sz[k] * probe.sz[k]);
    };
    double lo = 0.0, hi = 4.0 * limit + 1.0;
    for (int iteration = 0; iteration < 200 && target > 0; ++iteration) {
      const double mid = 0.5 * (lo + hi);
      (updated(mid) < target ? lo : hi) = mid;
    }
    const double size = target > 0 ? lo : 0.0;
    batch.sx[k] = size * t.x;
    batch.sy[k] = size * t.y;
    batch.sz[k] = size * t.z;
    near_limit += target > 0 && std::abs(updated(size) / limit - 1.0) < 1e-14;
  }
  EXPECT_GT(near_limit, 20);  // lanes within a few ulps of the cap were made
  reference = batch;
  law.template EvaluateBatch<true>(batch, count);
  OneLoopBatch(law, reference, count);
  int capped = 0;
  for (int k = 0; k < count; ++k) {
    const double got[] = {batch.sx[k],  batch.sy[k],  batch.sz[k],  batch.fx[k],
                          batch.fy[k],  batch.fz[k],  batch.tix[k], batch.tiy[k],
                          batch.tiz[k], batch.tjx[k], batch.tjy[k], batch.tjz[k]};
    const double want[] = {reference.sx[k],  reference.sy[k],  reference.sz[k],  reference.fx[k],
                           reference.fy[k],  reference.fz[k],  reference.tix[k], reference.tiy[k],
                           reference.tiz[k], reference.tjx[k], reference.tjy[k], reference.tjz[k]};
    for (int c = 0; c < 12; ++c) {
      EXPECT_EQ(std::memcmp(&got[c], &want[c], sizeof(double)), 0)
          << "pair " << k << " value " << c << ": " << got[c] << " against " << want[c];
    }
    capped += batch.capped[k] != 0;
  }
  // Both loops ran: some pairs were finished with the cap, most without.
  EXPECT_GT(capped, 10);
  EXPECT_LT(capped, count);
}

// ---------------------------------------------------------------------------
// Hertz–Mindlin.

TEST(HertzMindlin, NormalForceIsHertzsAndItsStiffnessIsTheDerivative) {
  const HertzMindlin::Params params{500e6, 0.25, 0.0};
  const HertzMindlin law(params, 1e-7);
  const double r_i = 0.5e-3, r_j = 0.2e-3, overlap = 3e-6;
  const double e_star = 500e6 / (2 * (1 - 0.25 * 0.25));
  const double r_star = r_i * r_j / (r_i + r_j);
  auto force = [&](double u) {
    return law.Evaluate<false>(StaticPair(r_i, r_j, u), {}).normal_force;
  };
  EXPECT_NEAR(force(overlap), 4.0 / 3.0 * e_star * std::sqrt(r_star) * std::pow(overlap, 1.5),
              1e-12 * force(overlap));
  const double h = 1e-3 * overlap;
  const double difference = (force(overlap + h) - force(overlap - h)) / (2 * h);
  const double stiffness = law.NormalStiffness(r_i, r_j, r_i + r_j - overlap);
  EXPECT_NEAR(stiffness, 2 * e_star * std::sqrt(r_star * overlap), 1e-12 * stiffness);
  EXPECT_NEAR(difference, stiffness, 1e-6 * stiffness);
  // Repulsive only, and F = 0 at first touch.
  EXPECT_EQ(force(0.0), 0.0);
  ContactResult result = law.Evaluate<false>(StaticPair(r_i, r_j, overlap), {});
  EXPECT_LT(result.force_i.x, 0.0);  // i is pushed away from j (along −x)
}

TEST(HertzMindlin, SlidingIsCappedAtTheCoulombLimitWithTheMindlinStiffness) {
  const double mu = std::tan(0.5), nu = 0.25, dt = 1e-7;
  const HertzMindlin law({500e6, nu, mu}, dt);
  const double r = 0.5e-3, overlap = 2e-6;
  ContactPair pair = StaticPair(r, r, overlap);
  pair.centre_velocity = {0, 0, -0.5};  // j slides along −z
  ContactResult result = law.Evaluate<true>(pair, {});
  // First increment: k_t Δt |v_t| with the no-slip Mindlin k_t = 8 G* √(R* u).
  const double shear_modulus = 500e6 / (2 * (1 + nu));
  const double g_star = shear_modulus / (2 * (2 - nu));
  const double k_t = 8 * g_star * std::sqrt(0.5 * r * overlap);
  EXPECT_NEAR(result.shear.z, -k_t * dt * 0.5, 1e-12 * k_t * dt * 0.5);
  EXPECT_EQ(result.shear.x, 0.0);
  for (int k = 0; k < 5000; ++k) result = law.Evaluate<true>(pair, {result.shear});
  const double limit = mu * result.normal_force;
  EXPECT_NEAR(Norm(result.shear), limit, 1e-12 * limit);
  EXPECT_LT(result.shear.z, 0.0);
  // The total force on i: −F_n n + F_s.
  EXPECT_NEAR(result.force_i.x, -result.normal_force, 1e-12 * result.normal_force);
  EXPECT_NEAR(result.force_i.z, result.shear.z, 1e-15);
}

TEST(HertzMindlin, StressAndAffineStiffnessSumsUseTheForceAndTheTangentStiffness) {
  const double r = 0.5e-3, overlap = 4e-6, side = 0.01;
  const Material material = Elastic(ContactLaw::kHertzMindlin);
  Engine engine(
      TwoSpheres({0.004, 0.005, 0.005}, {0.004 + 2 * r - overlap, 0.005, 0.005}, r, r, side),
      material, StepOptions(1e-8));
  engine.ComputeForces({true, true});
  const NormalResponse normal = NormalOf(material, r, r, overlap);
  const double l = 2 * r - overlap, volume = side * side * side;
  EXPECT_NEAR(engine.sums().stress[0], normal.force * l / volume,
              1e-12 * normal.force * l / volume);
  // dσ_11/dε_11 = (1/V) k_n l_1⁴/|l|² for a contact along axis 1.
  const double expected = normal.stiffness * l * l / volume;
  EXPECT_NEAR(engine.sums().stiffness[0], expected, 1e-12 * expected);
  for (int k = 1; k < 6; ++k) EXPECT_EQ(engine.sums().stiffness[k], 0.0);
  EXPECT_NEAR(normal.stiffness, 1.5 * normal.force / overlap, 1e-12 * normal.stiffness);
}

void CheckHeadOnImpact(const Material& material) {
  const double r_i = 0.5e-3, r_j = 0.3e-3, speed = 0.1;
  const double m_i = SphereMass(r_i, material.density), m_j = SphereMass(r_j, material.density);
  const double m_star = m_i * m_j / (m_i + m_j), r_star = r_i * r_j / (r_i + r_j);
  const double e_star = material.youngs_modulus / (2 * (1 - std::pow(material.poissons_ratio, 2)));
  // SPEC §8.1.
  const double expected =
      2.87 * std::pow(m_star * m_star / (r_star * e_star * e_star * speed), 0.2);
  const Impact impact = HeadOnImpact(material, r_i, r_j, speed, expected / 2000);
  EXPECT_NEAR(impact.duration, expected, 0.01 * expected);
  // With the exact constant 2.8683 the step count matches to a few steps.
  EXPECT_NEAR(impact.duration, expected * 2.8682657 / 2.87, 3 * expected / 2000);
  EXPECT_NEAR(impact.energy_after / impact.energy_before, 1.0, 1e-6);
  EXPECT_NEAR(impact.restitution, 1.0, 1e-6);
}

TEST(HertzMindlin, HeadOnImpactLastsTheHertzDurationAndConservesEnergy) {
  // With friction (head-on: no shear) and without (the frictionless kernels).
  for (double friction_angle : {0.5, 0.0}) {
    SCOPED_TRACE(friction_angle);
    CheckHeadOnImpact(Elastic(ContactLaw::kHertzMindlin, friction_angle));
  }
}

TEST(HertzMindlin, ContactDurationIsTheImpactAtTheReferenceSpeed) {
  const Material material = Elastic(ContactLaw::kHertzMindlin);
  const double r = 0.1e-3;
  const ContactDurations durations = ComputeContactDurations({r, r}, material);
  const Impact impact = HeadOnImpact(material, r, r, HertzMindlin::kReferenceImpactSpeed,
                                     durations.smallest_reduced_mass / 2000);
  EXPECT_NEAR(impact.duration, durations.smallest_reduced_mass,
              3 * durations.smallest_reduced_mass / 2000);
  // The leapfrog limit holds for every pair overlapping less than the
  // reference overlap, so it is below the duration by a wide margin.
  EXPECT_LT(durations.critical_time_step, 0.5 * durations.smallest_reduced_mass);
  EXPECT_NE(durations.description.find("Hertz"), std::string::npos);
}

// ---------------------------------------------------------------------------
// Rolling resistance.

template <class Normal>
void CheckRollingMomentCap(ContactLaw kind, double overlap) {
  const double mu_r = 0.1, dt = 1e-7, r_i = 0.5e-3, r_j = 0.3e-3;
  const RollingResistance<Normal> law =
      MakeLaw<RollingResistance<Normal>>(Elastic(kind, 0.5, mu_r), dt);
  ContactPair pair = StaticPair(r_i, r_j, overlap);
  // Counter-rotating like gears (no slip at the contact point, at the arms
  // r − u/2 from the centres): ω_i − ω_j along z.
  const double w = 200.0, arm_ratio = (r_i - 0.5 * overlap) / (r_j - 0.5 * overlap);
  pair.spin_i = {0, 0, w};
  pair.spin_j = {0, 0, -w * arm_ratio};
  ContactResult result = law.template Evaluate<true>(pair, {});
  const double r_star = r_i * r_j / (r_i + r_j);
  const double k_n = law.NormalStiffness(r_i, r_j, pair.distance);
  const double k_r = 2.25 * k_n * mu_r * mu_r * r_star * r_star;
  const double relative = w + w * arm_ratio;
  // First increment: elastic, opposing the relative rotation of i.
  EXPECT_NEAR(result.rolling.z, -k_r * dt * relative, 1e-12 * k_r * dt * relative);
  EXPECT_LT(Norm(result.shear), 1e-12 * result.normal_force);  // no slip
  const double limit = mu_r * r_star * result.normal_force;
  ASSERT_GT(limit, 0.0);
  double largest = 0.0;
  for (int k = 0; k < 20000; ++k) {
    result = law.template Evaluate<true>(pair, {result.shear, result.rolling});
    largest = std::max(largest, Norm(result.rolling));
  }
  EXPECT_LE(largest, limit * (1 + 1e-14));
  EXPECT_NEAR(Norm(result.rolling), limit, 1e-12 * limit);  // reached under continued rolling
  EXPECT_LT(result.rolling.z, 0.0);
  // The moment acts on i and, reversed, on j.
  EXPECT_NEAR(result.torque_i.z, result.rolling.z, 1e-12 * limit);
  EXPECT_NEAR(result.torque_j.z, -result.rolling.z, 1e-12 * limit);

  // A twist about the normal is not resisted.
  ContactPair twist = StaticPair(r_i, r_j, overlap);
  twist.spin_i = {w, 0, 0};
  EXPECT_LT(Norm(law.template Evaluate<true>(twist, {}).rolling), 1e-12 * limit);
}

TEST(RollingResistance, MomentGrowsWithTheRollingStiffnessUpToTheCapOnTheLinearLaw) {
  CheckRollingMomentCap<LinearCundallStrack>(ContactLaw::kLinear, 1e-6);
}

TEST(RollingResistance, MomentGrowsWithTheRollingStiffnessUpToTheCapOnHertzMindlin) {
  CheckRollingMomentCap<HertzMindlin>(ContactLaw::kHertzMindlin, 1e-5);
}

// Two equal spheres held at their centres, counter-rotating like gears: the
// contact rolls without slip, so only the rolling moment can slow them.
struct Gear {
  std::vector<double> spin;  // ω_z of sphere 0 per step (rad/s)
  double largest_moment_over_cap = 0;
  double moment_cap = 0;         // μ_r R* F_n (N m)
  double inverse_inertia = 0;    // 1/I (1/(kg m²))
  double rolling_stiffness = 0;  // k_r (N m/rad)
};
Gear RunGear(const Material& material, double overlap, double spin, double dt, int steps) {
  const double r = 0.5e-3;
  Engine engine(TwoSpheres({0.008, 0.01, 0.01}, {0.008 + 2 * r - overlap, 0.01, 0.01}, r, r),
                material, StepOptions(dt));
  const double inverse_inertia = 1.0 / (0.4 * SphereMass(r, material.density) * r * r);
  for (int id = 0; id < 2; ++id) {
    engine.SetInverseMassAndInertia(Slot(engine, id), 0.0, inverse_inertia);
    engine.SetSpin(Slot(engine, id), {0, 0, id == 0 ? spin : -spin});
  }
  Gear gear;
  gear.inverse_inertia = inverse_inertia;
  const NormalResponse normal = NormalOf(material, r, r, overlap);
  gear.moment_cap = material.rolling_friction * 0.5 * r * normal.force;
  gear.rolling_stiffness = RollingStiffness(material.rolling_friction, 0.5 * r, normal.stiffness);
  double asymmetry = 0.0;
  for (int step = 0; step < steps; ++step) {
    engine.Step();
    const size_t first = Slot(engine, 0);
    gear.spin.push_back(engine.spins()[first].z);
    asymmetry =
        std::max(asymmetry, std::abs(engine.spins()[first].z + engine.spins()[Slot(engine, 1)].z));
    if (material.has_rolling_resistance()) {
      EXPECT_EQ(engine.neighbors().rolling().size(), 1u);
      gear.largest_moment_over_cap = std::max(
          gear.largest_moment_over_cap, Norm(engine.neighbors().rolling()[0]) / gear.moment_cap);
    }
  }
  // Equal and opposite spins up to rounding (a fused multiply-add leaves the
  // contact slip at ~1e-16 of the spins instead of exactly 0), so rolling
  // without slip: no shear force beyond rounding.
  EXPECT_LT(asymmetry, 1e-9 * spin);
  EXPECT_LT(Norm(engine.neighbors().shear()[0]), 1e-9 * normal.force);
  return gear;
}

void CheckGearRollsToRest(ContactLaw kind, double overlap) {
  const double dt = 1e-8, spin = 3000.0;
  // Undamped: the moment rises to the cap and then decelerates both spheres
  // at M_cap/I (plastic rolling) until the spring can hold them; then they
  // oscillate elastically within the cap.
  Material material = Elastic(kind, 0.5, 0.1);
  const Gear plastic = RunGear(material, overlap, spin, dt, 60000);
  EXPECT_LE(plastic.largest_moment_over_cap, 1 + 1e-12);
  EXPECT_GE(plastic.largest_moment_over_cap, 1 - 1e-12);  // the cap is reached
  // The deceleration over a window well inside the plastic phase.
  const double deceleration_time = spin / (plastic.moment_cap * plastic.inverse_inertia);
  const int early = static_cast<int>(0.4 * deceleration_time / dt);
  const int late = 2 * early;
  ASSERT_GT(early, 200);
  const double rate = (plastic.spin[early] - plastic.spin[late]) / ((late - early) * dt);
  EXPECT_NEAR(rate, plastic.moment_cap * plastic.inverse_inertia,
              1e-6 * plastic.moment_cap * plastic.inverse_inertia);
  // After the plastic phase the spin stays within the elastic bound
  // M_cap/sqrt(2 I k_r): the spheres no longer roll on.
  const double elastic_bound =
      plastic.moment_cap * std::sqrt(plastic.inverse_inertia / (2 * plastic.rolling_stiffness));
  ASSERT_LT(elastic_bound, 0.8 * spin);
  ASSERT_LT(2 * deceleration_time / dt, plastic.spin.size());
  for (size_t k = static_cast<size_t>(2 * deceleration_time / dt); k < plastic.spin.size(); ++k) {
    ASSERT_LE(std::abs(plastic.spin[k]), 1.01 * elastic_bound) << k;
  }

  // With local damping the remaining oscillation dies out: at rest.
  material.local_damping = 0.5;
  const Gear damped = RunGear(material, overlap, spin, dt, 300000);
  EXPECT_LT(std::abs(damped.spin.back()), 1e-3 * spin);
  // Without rolling resistance nothing slows the gears, damped or not.
  material.rolling_friction = 0.0;
  const Gear free = RunGear(material, overlap, spin, dt, 2000);
  EXPECT_NEAR(free.spin.back(), spin, 1e-9 * spin);
}

TEST(RollingResistance, CounterRotatingSpheresRollToRestOnTheLinearLaw) {
  CheckGearRollsToRest(ContactLaw::kLinear, 1e-6);
}

TEST(RollingResistance, CounterRotatingSpheresRollToRestOnHertzMindlin) {
  CheckGearRollsToRest(ContactLaw::kHertzMindlin, 1e-5);
}

// 27 spheres on a simple cubic lattice, each pressed onto its six neighbours,
// with random velocities and spins.
Packing Lattice() {
  Packing packing;
  const double r = 0.5e-3, spacing = 2 * r - 2e-6;
  packing.cell = {3 * spacing, 3 * spacing, 3 * spacing};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      for (int k = 0; k < 3; ++k) {
        packing.positions.push_back(
            {(i + 0.5) * spacing, (j + 0.5) * spacing, (k + 0.5) * spacing});
        packing.radii.push_back(r);
      }
    }
  }
  return packing;
}

void Shake(Engine& engine) {
  SplitMix64 random(11);
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * random.Uniform(); };
  for (size_t i = 0; i < engine.size(); ++i) {
    engine.SetVelocity(i, {uniform(-0.02, 0.02), uniform(-0.02, 0.02), uniform(-0.02, 0.02)});
    engine.SetSpin(i, {uniform(-200, 200), uniform(-200, 200), uniform(-200, 200)});
  }
}

TEST(RollingResistance, ASecondEvaluationAppliesTheStoredMomentsAndSaveRestoreContinues) {
  for (ContactLaw kind : {ContactLaw::kLinear, ContactLaw::kHertzMindlin}) {
    SCOPED_TRACE(ToString(kind));
    const Material material = Elastic(kind, 0.5, 0.2);
    Engine once(Lattice(), material, StepOptions(1e-8));
    Engine twice(Lattice(), material, StepOptions(1e-8));
    Shake(once);
    Shake(twice);
    for (int step = 0; step < 50; ++step) {
      once.Step();
      twice.Step();
    }
    // A second evaluation at the same positions (the scalar path with the
    // stored history) neither advances the moments nor changes the torques.
    once.ComputeForces({});
    twice.ComputeForces({});
    const std::vector<Vec3> moments = twice.neighbors().rolling();
    twice.ComputeForces({true, true});
    EXPECT_EQ(twice.neighbors().rolling().size(), moments.size());
    for (size_t p = 0; p < moments.size(); ++p) {
      EXPECT_EQ(twice.neighbors().rolling()[p].x, moments[p].x);
    }
    once.Integrate();
    twice.Integrate();
    double largest_spin = 0;
    for (size_t i = 0; i < once.size(); ++i)
      largest_spin = std::max(largest_spin, Norm(Xyz(once.spins()[i])));
    for (size_t i = 0; i < once.size(); ++i) {
      EXPECT_NEAR(once.spins()[i].x, twice.spins()[i].x, 1e-12 * largest_spin);
      EXPECT_NEAR(once.spins()[i].z, twice.spins()[i].z, 1e-12 * largest_spin);
    }
    int loaded = 0;
    for (const Vec3& m : once.neighbors().rolling()) loaded += Norm(m) > 0;
    EXPECT_GT(loaded, 20);  // the lattice's 81 contacts carry moments

    // Save, continue, restore into a fresh engine, continue: bit-identical.
    const Engine::State saved = once.Save();
    for (int step = 0; step < 50; ++step) once.Step();
    Engine restored(Lattice(), material, StepOptions(1e-8));
    restored.Restore(saved);
    for (int step = 0; step < 50; ++step) restored.Step();
    for (size_t i = 0; i < once.size(); ++i) {
      EXPECT_EQ(once.spins()[i].y, restored.spins()[i].y);
      EXPECT_EQ(once.velocities()[i].x, restored.velocities()[i].x);
    }
    EXPECT_EQ(once.neighbors().rolling()[3].z, restored.neighbors().rolling()[3].z);
  }
}

}  // namespace
}  // namespace granasym::dem
