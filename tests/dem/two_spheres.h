// Two-sphere set-ups shared by the engine and contact-law tests.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdint>

#include "dem/contact_statistics.h"
#include "dem/engine.h"
#include "dem/material.h"
#include "dem/packing.h"

namespace granasym::dem::testing {

inline Packing TwoSpheres(std::array<double, 3> a, std::array<double, 3> b, double radius_a,
                          double radius_b, double side = 0.02) {
  Packing packing;
  packing.cell = {side, side, side};
  packing.positions = {a, b};
  packing.radii = {radius_a, radius_b};
  return packing;
}

inline Engine::Options StepOptions(double dt, int threads = 1) {
  Engine::Options options;
  options.time_step = dt;
  options.threads = threads;
  return options;
}

// Index in the engine of the sphere with input index `id`.
inline size_t Slot(const Engine& engine, int64_t id) {
  for (size_t k = 0; k < engine.size(); ++k) {
    if (engine.ids()[k] == id) return k;
  }
  return engine.size();
}

// A head-on impact of two free spheres at relative speed `speed`: the number
// of steps in contact times Δt, and the kinetic energies before and after.
struct Impact {
  double duration, energy_before, energy_after, restitution;
};
inline Impact HeadOnImpact(const Material& material, double r_i, double r_j, double speed,
                           double dt) {
  const double gap = 1e-3 * (r_i + r_j);
  Engine engine(TwoSpheres({0.008, 0.01, 0.01}, {0.008 + r_i + r_j + gap, 0.01, 0.01}, r_i, r_j),
                material, StepOptions(dt));
  engine.SetVelocity(Slot(engine, 0), {0.5 * speed, 0, 0});
  engine.SetVelocity(Slot(engine, 1), {-0.5 * speed, 0, 0});
  Impact impact{};
  impact.energy_before = KineticEnergy(engine);
  int contact_steps = 0;
  bool touched = false;
  for (int step = 0; step < 10000000; ++step) {
    engine.Step({true, false});
    if (engine.sums().contacts > 0) {
      ++contact_steps;
      touched = true;
    } else if (touched) {
      break;
    }
  }
  EXPECT_TRUE(touched);
  impact.duration = contact_steps * dt;
  impact.energy_after = KineticEnergy(engine);
  const double approach =
      engine.velocities()[Slot(engine, 0)].x - engine.velocities()[Slot(engine, 1)].x;
  impact.restitution = -approach / speed;
  return impact;
}

}  // namespace granasym::dem::testing
