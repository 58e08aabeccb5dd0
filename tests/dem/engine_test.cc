#include "dem/engine.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iomanip>

#include "dem/contact_statistics.h"
#include "dem/grain_size_distribution.h"
#include "dem/packing.h"
#include "two_spheres.h"

namespace granasym::dem {
namespace {

using testing::HeadOnImpact;
using testing::Impact;
using testing::Slot;
using testing::StepOptions;
using testing::TwoSpheres;

Material Elastic(double friction_angle = 0.0) {
  Material material;
  material.youngs_modulus = 500e6;
  material.stiffness_ratio = 0.3;
  material.friction_angle = friction_angle;
  material.density = 2650.0;
  material.local_damping = 0.0;
  return material;
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
  const Impact impact = HeadOnImpact(material, r, r, 2 * speed, dt);
  EXPECT_NEAR(impact.duration, contact_duration, 2.0 * dt);
  EXPECT_NEAR(impact.energy_after / impact.energy_before, 1.0, 1e-6);
  EXPECT_NEAR(impact.restitution, 1.0, 1e-6);
}

// Forces on two overlapping spheres placed at `a` and `a + offset`.
std::array<Vec3, 2> PairForces(std::array<double, 3> a, std::array<double, 3> offset) {
  std::array<double, 3> b = {a[0] + offset[0], a[1] + offset[1], a[2] + offset[2]};
  const double side = 0.01;
  for (double& x : b) x -= side * std::floor(x / side);
  Engine engine(TwoSpheres(a, b, 0.5e-3, 0.5e-3, side), Elastic(0.5), StepOptions(1e-8));
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
  Engine engine(TwoSpheres({0.004, 0.004, 0.004}, {0.004 + 0.95e-3, 0.0042, 0.004}, r, r, 0.01),
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

TEST(Engine, ANewTimeStepMovesTheNextStepAndItsShearIncrementByTheNewStep) {
  // Two held spheres in contact (1/m = 0: their velocities stay as set), the
  // second sliding past the first at v along y: each force evaluation adds
  // k_s Δt v to the shear force, the Δt of the step that made that slide.
  const double r = 0.5e-3, overlap = 2e-6, v = 0.01, dt = 1e-8;
  Engine engine(
      TwoSpheres({0.004, 0.005, 0.005}, {0.004 + 2 * r - overlap, 0.005, 0.005}, r, r, 0.01),
      Elastic(0.5), StepOptions(dt));
  for (int64_t id : {0, 1}) engine.SetInverseMassAndInertia(Slot(engine, id), 0.0, 0.0);
  engine.SetVelocity(Slot(engine, 1), {0.0, v, 0.0});
  const double k_s = 0.3 * 500e6 * r;
  // The stored shear force of the one pair (on sphere 0 or 1, whichever the
  // list made i: its magnitude).
  auto shear = [&engine] {
    EXPECT_EQ(engine.neighbors().shear().size(), 1u);
    return Norm(engine.neighbors().shear().at(0));
  };
  engine.ComputeForces({false, false});
  const double first = shear();
  EXPECT_NEAR(first, k_s * dt * v, 1e-9 * k_s * dt * v);
  engine.SetTimeStep(0.5 * dt);
  EXPECT_EQ(engine.time_step(), 0.5 * dt);
  engine.Integrate();
  EXPECT_EQ(engine.time(), 0.5 * dt);
  EXPECT_NEAR(engine.Position(Slot(engine, 1)).y, 0.005 + 0.5 * dt * v, 1e-15);
  engine.ComputeForces({false, false});
  // The increment is k_s (Δt/2) v: the slide of the step just taken.
  const double increment = shear() - first;
  EXPECT_NEAR(increment, k_s * 0.5 * dt * v, 1e-6 * k_s * dt * v);
  // The state carries Δt: an engine restored from it steps with it.
  Engine restored(
      TwoSpheres({0.004, 0.005, 0.005}, {0.004 + 2 * r - overlap, 0.005, 0.005}, r, r, 0.01),
      Elastic(0.5), StepOptions(dt));
  restored.Restore(engine.Save());
  EXPECT_EQ(restored.time_step(), 0.5 * dt);
  engine.Integrate();
  restored.ComputeForces({false, false});
  restored.Integrate();
  EXPECT_EQ(restored.time(), engine.time());
  EXPECT_EQ(restored.Position(Slot(restored, 1)).y, engine.Position(Slot(engine, 1)).y);
}

TEST(Engine, LoveWeberStressOfOneNormalContact) {
  const double r = 0.5e-3, overlap = 2e-6, side = 0.01;
  Engine engine(
      TwoSpheres({0.004, 0.005, 0.005}, {0.004 + 2 * r - overlap, 0.005, 0.005}, r, r, side),
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

// Engine::Step advances each particle inside the force pass; it must give
// exactly what ComputeForces + Integrate give, for every kernel variant it
// can select (friction or not, rolling resistance, damping or not, stress
// sums), on one thread (advanced inline) and on several (after the barrier).
// The four doubles of a particle record, for exact comparison.
std::array<double, 4> Bits(const Vec4& v) { return {v.x, v.y, v.z, v.w}; }

// 600 spheres of the paper's GSD at the paper's density of the cell.
Packing SmallSample(uint64_t seed) {
  GenerationOptions generation;
  generation.count = 600;
  generation.cell_size = 31e-3 * std::cbrt(600.0 / 150000.0);
  generation.seed = seed;
  return GeneratePacking(GrainSizeDistribution::Default(), generation);
}

TEST(Engine, TheFusedStepIsBitIdenticalToForcesThenIntegration) {
  const Packing packing = SmallSample(5);
  struct Variant {
    const char* name;
    double friction_angle, local_damping, rolling;
    ContactLaw law;
  };
  const Variant variants[] = {
      {"frictionless, undamped", 0.0, 0.0, 0.0, ContactLaw::kLinear},
      {"frictional, damped", 0.5, 0.5, 0.0, ContactLaw::kLinear},
      {"Hertz, rolling resistance", 0.5, 0.3, 0.1, ContactLaw::kHertzMindlin}};
  for (const Variant& variant : variants) {
    for (int threads : {1, 2, 3}) {
      SCOPED_TRACE(std::string(variant.name) + ", " + std::to_string(threads) + " threads");
      Material material = Elastic(variant.friction_angle);
      material.local_damping = variant.local_damping;
      material.rolling_friction = variant.rolling;
      material.contact_law = variant.law;
      Engine fused(packing, material, StepOptions(1.2e-7, threads));
      Engine separate(packing, material, StepOptions(1.2e-7, threads));
      for (Engine* engine : {&fused, &separate}) engine->SetVelocityGradient({-500, -500, -500});
      int64_t contacts = 0;
      for (int step = 0; step < 3000; ++step) {
        const Engine::Request request{step % 7 == 0, step % 11 == 0};
        fused.Step(request);
        separate.ComputeForces(request);
        separate.Integrate();
        if (request.stress) {
          ASSERT_EQ(fused.sums().stress, separate.sums().stress) << "step " << step;
          contacts = fused.sums().contacts;
        }
        if (request.stiffness) {
          for (int k = 0; k < 6; ++k)
            ASSERT_EQ(fused.sums().stiffness[k], separate.sums().stiffness[k])
                << "step " << step << " k " << k << std::setprecision(17) << " "
                << fused.sums().stiffness[k] - separate.sums().stiffness[k];
        }
      }
      EXPECT_GT(contacts, 600);  // compressed into a contact network (Z > 2)
      EXPECT_EQ(fused.neighbors().builds(), separate.neighbors().builds());
      EXPECT_GT(fused.neighbors().builds(), 1);
      EXPECT_EQ(fused.cell(), separate.cell());
      EXPECT_EQ(fused.time(), separate.time());
      EXPECT_EQ(fused.step(), separate.step());
      for (size_t i = 0; i < fused.size(); ++i) {
        ASSERT_EQ(Bits(fused.scaled_positions()[i]), Bits(separate.scaled_positions()[i])) << i;
        ASSERT_EQ(Bits(fused.velocities()[i]), Bits(separate.velocities()[i])) << i;
        ASSERT_EQ(Bits(fused.spins()[i]), Bits(separate.spins()[i])) << i;
        ASSERT_EQ(Bits(fused.forces()[i]), Bits(separate.forces()[i])) << i;
      }
    }
  }
}

// The skin decides only which non-touching pairs are listed and when the
// list is rebuilt (positions are not wrapped at a build): the results do not
// depend on it, bit for bit, so it is a pure performance setting. Nor do
// they depend on the near list's skin (where it starts: it adapts) and when
// that list is rebuilt.
TEST(Engine, ResultsDoNotDependOnTheSkin) {
  const Packing packing = SmallSample(9);
  for (ContactLaw law : {ContactLaw::kLinear, ContactLaw::kHertzMindlin}) {
    for (int threads : {1, 2, 3}) {
      SCOPED_TRACE(std::string(ToString(law)) + ", " + std::to_string(threads) + " threads");
      Material material = Elastic(0.5);
      material.local_damping = 0.5;
      material.contact_law = law;
      Engine::Options thick = StepOptions(1.2e-7, threads), thin = thick;
      thick.skin_fraction = 0.3;
      thin.skin_fraction = 0.02;
      Engine::Options whole = thick, narrow = thick;
      whole.near_skin_ratio = 1.0;
      narrow.near_skin_ratio = 1.0 / 64;
      Engine a(packing, material, thick), b(packing, material, thin);
      Engine c(packing, material, whole), d(packing, material, narrow);
      int64_t contacts = 0;
      for (int step = 0; step < 4000; ++step) {
        // Compression into a contact network, then isochoric shear, which
        // carries particles across the periodic boundaries.
        const std::array<double, 3> gradient = step < 2000 ? std::array<double, 3>{-500, -500, -500}
                                                           : std::array<double, 3>{-400, 200, 200};
        const Engine::Request request{step % 7 == 0, step % 11 == 0};
        for (Engine* engine : {&a, &b, &c, &d}) {
          engine->SetVelocityGradient(gradient);
          if (step % 3 == 0) {
            engine->ComputeForces(request);
            engine->Integrate();
          } else {
            engine->Step(request);
          }
        }
        for (const Engine* other : {&b, &c, &d}) {
          if (request.stress) {
            ASSERT_EQ(a.sums().stress, other->sums().stress) << "step " << step;
            ASSERT_EQ(a.sums().force_sum, other->sums().force_sum) << "step " << step;
          }
          if (request.stiffness) {
            ASSERT_EQ(a.sums().stiffness, other->sums().stiffness) << "step " << step;
          }
        }
        if (request.stress) contacts = std::max(contacts, a.sums().contacts);
      }
      EXPECT_GT(contacts, 600);  // a contact network (Z > 2) at the end of compression
      EXPECT_GT(b.neighbors().builds(), 2 * a.neighbors().builds());
      EXPECT_LT(b.neighbors().pair_count(), a.neighbors().pair_count());
      // The near lists: rebuilt on their own between the neighbour list's
      // builds, and fewer pairs than listed.
      EXPECT_GT(d.near_pairs().builds(), c.near_pairs().builds());
      EXPECT_GT(d.near_pairs().builds(), d.neighbors().builds());
      EXPECT_LT(d.near_pairs().pair_count(), static_cast<int64_t>(d.neighbors().pair_count()));
      EXPECT_LT(a.near_pairs().skin(), a.neighbors().skin());
      bool outside = false;  // some particle left the cell [0, 1) unwrapped
      for (const Engine* other : {&b, &c, &d}) {
        EXPECT_EQ(a.cell(), other->cell());
        for (size_t i = 0; i < a.size(); ++i) {
          ASSERT_EQ(Bits(a.scaled_positions()[i]), Bits(other->scaled_positions()[i])) << i;
          ASSERT_EQ(Bits(a.velocities()[i]), Bits(other->velocities()[i])) << i;
          ASSERT_EQ(Bits(a.spins()[i]), Bits(other->spins()[i])) << i;
          ASSERT_EQ(Bits(a.forces()[i]), Bits(other->forces()[i])) << i;
        }
      }
      for (size_t i = 0; i < a.size(); ++i) {
        const Vec4& s = a.scaled_positions()[i];
        outside = outside || s.x < 0 || s.x >= 1 || s.y < 0 || s.y >= 1 || s.z < 0 || s.z >= 1;
      }
      EXPECT_TRUE(outside);
    }
  }
}

// The near list is derived state: an engine restored from a state saved
// mid-run (after a step, or after ComputeForces with the forces current)
// builds it at the restored positions, at other steps than the running
// engine, and must continue bit for bit, its contact histories too (the
// near build clears a left-out pair's history exactly as the force pass
// would). The engine restored into may also have run before, on another
// sample: nothing of that run (its lists, its threads' halos) may leak in.
TEST(Engine, ARestoredEngineRebuildsItsNearListAndContinuesBitIdentically) {
  const Packing packing = SmallSample(4);
  Material material = Elastic(0.5);
  material.local_damping = 0.5;
  for (int threads : {1, 2, 3}) {
    for (bool forces_current : {false, true}) {
      const bool used = threads > 1 && forces_current;
      SCOPED_TRACE(std::to_string(threads) + " threads, forces current " +
                   std::to_string(forces_current) + ", restored into a used engine " +
                   std::to_string(used));
      const Engine::Options options = StepOptions(1.2e-7, threads);
      Engine running(packing, material, options);
      auto advance = [](Engine& engine, int step) {
        engine.SetVelocityGradient(step < 2000 ? std::array<double, 3>{-500, -500, -500}
                                               : std::array<double, 3>{-400, 200, 200});
        if (step % 5 == 0) {
          engine.ComputeForces({true, false});
          engine.ComputeForces({true, true});  // again at the same positions
          engine.Integrate();
        } else {
          engine.Step();
        }
      };
      for (int step = 0; step < 2200; ++step) advance(running, step);
      if (forces_current) running.ComputeForces({});
      const Engine::State saved = running.Save();
      // A used engine: another sample of the same size, compressed likewise.
      Engine restored(used ? SmallSample(9) : packing, material, options);
      if (used) {
        for (int step = 0; step < 2200; ++step) advance(restored, step);
      }
      restored.Restore(saved);
      const int64_t near_builds = running.near_pairs().builds();
      for (int step = 2200; step < 3100; ++step) {
        advance(running, step);
        advance(restored, step);
        if (step % 5 == 0) {
          ASSERT_EQ(running.sums().stress, restored.sums().stress) << step;
          ASSERT_EQ(running.sums().stiffness, restored.sums().stiffness) << step;
        }
      }
      EXPECT_GT(running.near_pairs().builds(), near_builds + 5);
      EXPECT_GT(running.sums().contacts, 400);  // still a contact network (Z ≈ 1.5)
      for (size_t i = 0; i < running.size(); ++i) {
        ASSERT_EQ(Bits(running.scaled_positions()[i]), Bits(restored.scaled_positions()[i])) << i;
        ASSERT_EQ(Bits(running.velocities()[i]), Bits(restored.velocities()[i])) << i;
        ASSERT_EQ(Bits(running.spins()[i]), Bits(restored.spins()[i])) << i;
      }
      const std::vector<Vec3>& a = running.neighbors().shear();
      const std::vector<Vec3>& b = restored.neighbors().shear();
      ASSERT_EQ(a.size(), b.size());
      int64_t loaded = 0;
      for (size_t p = 0; p < a.size(); ++p) {
        ASSERT_EQ(a[p].x, b[p].x) << p;
        ASSERT_EQ(a[p].y, b[p].y) << p;
        ASSERT_EQ(a[p].z, b[p].z) << p;
        loaded += a[p].x != 0;
      }
      EXPECT_GT(loaded, 400);
    }
  }
}

// On several threads a sphere's force is its sums in other order: the
// halos of the threads before its owner (only for the spheres their pairs
// reach), then the owner's own. So forces and torques agree with one
// thread's to rounding; a halo left out or left over (not zeroed for the
// next evaluation) would be off by a whole contact force. Each engine
// evaluates at several states of one run, restored in turn.
TEST(Engine, ForcesOnSeveralThreadsAreThoseOfOneUpToTheOrderOfTheSums) {
  const Packing packing = SmallSample(6);
  Material material = Elastic(0.5);
  material.local_damping = 0.5;
  material.rolling_friction = 0.1;
  material.contact_law = ContactLaw::kHertzMindlin;
  Engine running(packing, material, StepOptions(1.2e-7, 1));
  Engine one(packing, material, StepOptions(1.2e-7, 1));
  std::vector<Engine> several;
  for (int threads : {2, 3, 4})
    several.emplace_back(packing, material, StepOptions(1.2e-7, threads));
  int checked = 0;
  for (int step = 0; step < 3000; ++step) {
    running.SetVelocityGradient(step < 2000 ? std::array<double, 3>{-500, -500, -500}
                                            : std::array<double, 3>{-400, 200, 200});
    running.Step();
    if (step < 1500 || step % 250 != 0) continue;
    const Engine::State state = running.Save();
    one.Restore(state);
    one.ComputeForces({true, false});
    double largest = 0;
    for (const Vec4& f : one.forces()) largest = std::max(largest, Norm(Vec3{f.x, f.y, f.z}));
    double largest_torque = 0;
    for (const Vec4& m : one.torques())
      largest_torque = std::max(largest_torque, Norm(Vec3{m.x, m.y, m.z}));
    ASSERT_GT(largest, 0);
    ASSERT_GT(largest_torque, 0);
    for (Engine& engine : several) {
      SCOPED_TRACE(std::to_string(engine.options().threads) + " threads, step " +
                   std::to_string(step));
      engine.Restore(state);
      engine.ComputeForces({true, false});
      EXPECT_EQ(engine.sums().contacts, one.sums().contacts);
      for (size_t i = 0; i < one.size(); ++i) {
        const Vec4 &f = one.forces()[i], &g = engine.forces()[i];
        ASSERT_LE(Norm(Vec3{f.x - g.x, f.y - g.y, f.z - g.z}), 1e-12 * largest) << i;
        const Vec4 &m = one.torques()[i], &n = engine.torques()[i];
        ASSERT_LE(Norm(Vec3{m.x - n.x, m.y - n.y, m.z - n.z}), 1e-12 * largest_torque) << i;
      }
    }
    ++checked;
  }
  EXPECT_EQ(checked, 6);
  EXPECT_GT(one.sums().contacts, 400);  // a contact network
}

}  // namespace
}  // namespace granasym::dem
