// Rolling resistance between spheres: the elastic–plastic rolling spring of
// Ai et al. (2011, Powder Technol. 206, 269; their model C without the
// viscous term), SPEC §8.1, added to a normal law.
//
//   k_r = 2.25 k_n μ_r² R*²,  M_r ← R M_r − k_r Δθ_r,  |M_r| ≤ μ_r R* F_n,
// with R* = r_i r_j/(r_i + r_j), k_n the law's tangent normal stiffness at the
// current overlap (for the linear law its constant k_n), R the rigid rotation
// of the contact that also carries the shear force (contact_law.h), and
// Δθ_r = Δt (ω_i − ω_j)_t the relative rolling rotation over the step: the
// part of the relative angular velocity in the tangent plane (the twist about
// n is not resisted). M_r acts on i and −M_r on j; it does no work on the
// centres and enters no force, so the Love–Weber stress is unchanged.
//
// Design: a decorator. RollingResistance<Law> wraps any normal law (Linear
// Cundall–Strack, Hertz–Mindlin) and is itself a law (contact_law.h): its
// EvaluateBatch runs the wrapped law's batch unchanged and then a second
// vectorised pass over the same batch that adds the rolling moments, and its
// scalar Evaluate does the same on one pair. The normal laws stay untouched
// (the paper's law keeps its code and its speed), the rolling physics is
// written once for both, and the pair loop instantiates the rolling kernels
// only for scenes that use them (kRollingHistory makes the loop keep one
// moment per pair, NeighborList::rolling()). The second pass recomputes n,
// F_n and k_n from the batch's branch vectors (a square root and a division
// per contact) rather than making every law store them.
#pragma once

#include <cmath>
#include <string>

#include "dem/contact_law.h"
#include "dem/material.h"

namespace granasym::dem {

// The rolling stiffness k_r = 2.25 μ_r² R*² k_n (N m/rad).
inline double RollingStiffness(double rolling_friction, double reduced_radius,
                               double normal_stiffness) {
  return 2.25 * rolling_friction * rolling_friction * reduced_radius * reduced_radius *
         normal_stiffness;
}

template <class Law>
class RollingResistance {
 public:
  struct Params {
    typename Law::Params law;
    double rolling_friction = 0.0;  // μ_r (dimensionless)
    bool IsValid(std::string* why) const {
      if (!law.IsValid(why)) return false;
      if (!(rolling_friction >= 0)) return *why = "rolling_friction must be >= 0", false;
      return true;
    }
    static Params FromMaterial(const Material& material) {
      return {Law::Params::FromMaterial(material), material.rolling_friction};
    }
  };
  static constexpr bool kRollingHistory = true;
  static constexpr bool kOverlapDependentStiffness = Law::kOverlapDependentStiffness;

  RollingResistance(const Params& params, double time_step)
      : law_(params.law, time_step),
        params_(params),
        stiffness_factor_(2.25 * params.rolling_friction * params.rolling_friction) {}

  double NormalStiffness(double radius_i, double radius_j, double distance) const {
    return law_.NormalStiffness(radius_i, radius_j, distance);
  }

  // The wrapped law's evaluation plus the rolling moment: history.rolling is
  // advanced and returned in ContactResult::rolling, or with kFrozen applied
  // as it is. Rolling resistance acts on spins, so it needs kFriction.
  template <bool kFriction, bool kFrozen = false>
  ContactResult Evaluate(const ContactPair& pair, const ContactHistory& history) const {
    static_assert(kFriction, "rolling resistance needs friction (spins)");
    ContactResult result = law_.template Evaluate<kFriction, kFrozen>(pair, history);
    Vec3 moment = history.rolling;
    if constexpr (!kFrozen) {
      const double reach = pair.radius_i + pair.radius_j;
      const double overlap = reach - pair.distance;
      const double reciprocal = 1.0 / (reach * pair.distance);
      const double inverse_distance = reach * reciprocal;
      const Vec3 normal = inverse_distance * pair.branch;
      const NormalResponse response =
          law_.Normal(pair.radius_i, pair.radius_j, pair.distance, reciprocal, overlap);
      const double reduced_radius = pair.radius_i * pair.radius_j * (pair.distance * reciprocal);
      const double dt = law_.time_step();
      moment =
          CarryWithContact(moment, ContactRotation(pair, normal, inverse_distance, dt), normal);
      const Vec3 relative_spin = pair.spin_i - pair.spin_j;
      const Vec3 rolling_rate = relative_spin - Dot(relative_spin, normal) * normal;
      const double k_r = stiffness_factor_ * reduced_radius * reduced_radius * response.stiffness;
      moment = moment - (k_r * dt) * rolling_rate;
      const double limit = params_.rolling_friction * reduced_radius * response.force;
      const double magnitude2 = Dot(moment, moment);
      if (magnitude2 > limit * limit) moment = (limit / std::sqrt(magnitude2)) * moment;
    }
    result.rolling = moment;
    result.torque_i = result.torque_i + moment;
    result.torque_j = result.torque_j - moment;
    return result;
  }

  template <bool kFriction>
  void EvaluateBatch(ContactBatch& b, int count) const {
    static_assert(kFriction, "rolling resistance needs friction (spins)");
    law_.template EvaluateBatch<kFriction>(b, count);
    const double mu_r = params_.rolling_friction;
    const double factor = stiffness_factor_;
    const double dt = law_.time_step();
#pragma omp simd
    for (int k = 0; k < count; ++k) {
      const LaneGeometry g = ContactGeometryLane(b, k);
      const double distance = g.distance, overlap = g.overlap, reciprocal = g.reciprocal;
      const double inverse_distance = g.inverse_distance, nx = g.nx, ny = g.ny, nz = g.nz;
      const NormalResponse response = law_.Normal(b.ri[k], b.rj[k], distance, reciprocal, overlap);
      const double reduced_radius = b.ri[k] * b.rj[k] * (distance * reciprocal);
      double rx, ry, rz;
      ContactRotationLane(b, k, nx, ny, nz, inverse_distance, dt, rx, ry, rz);
      double mx = b.rmx[k], my = b.rmy[k], mz = b.rmz[k];
      CarryWithContactLane(rx, ry, rz, nx, ny, nz, mx, my, mz);
      // Relative rolling rate ω_i − ω_j, tangential part.
      const double wx = b.wix[k] - b.wjx[k], wy = b.wiy[k] - b.wjy[k], wz = b.wiz[k] - b.wjz[k];
      const double wn = wx * nx + wy * ny + wz * nz;
      const double k_r_dt = factor * reduced_radius * reduced_radius * response.stiffness * dt;
      mx -= k_r_dt * (wx - wn * nx);
      my -= k_r_dt * (wy - wn * ny);
      mz -= k_r_dt * (wz - wn * nz);
      CapLane(mu_r * reduced_radius * response.force, mx, my, mz);
      b.rmx[k] = mx;
      b.rmy[k] = my;
      b.rmz[k] = mz;
      b.tix[k] += mx;
      b.tiy[k] += my;
      b.tiz[k] += mz;
      b.tjx[k] -= mx;
      b.tjy[k] -= my;
      b.tjz[k] -= mz;
    }
  }

  const Law& law() const { return law_; }
  const Params& params() const { return params_; }
  double time_step() const { return law_.time_step(); }

  // Durations are the wrapped law's; ComputeContactDurations adds the rolling
  // spring to the stability limit (RollingStiffness).
  static double ImpactDuration(const Params& params, double radius, double mass) {
    return Law::ImpactDuration(params.law, radius, mass);
  }
  static double StabilityStiffness(const Params& params, double radius_i, double radius_j) {
    return Law::StabilityStiffness(params.law, radius_i, radius_j);
  }
  static double TangentialStiffnessRatio(const Params& params) {
    return Law::TangentialStiffnessRatio(params.law);
  }
  // The wrapped law's κ: the rolling spring does not change the overlaps.
  static double StiffnessNumber(const Params& params, double mean_stress) {
    return Law::StiffnessNumber(params.law, mean_stress);
  }
  static std::string DurationDescription() {
    return Law::DurationDescription() +
           "; rolling resistance: omega_max^2 also bounded by k_r (1/I_i + 1/I_j), "
           "k_r = 2.25 mu_r^2 R*^2 k_n";
  }

 private:
  Law law_;
  Params params_;
  double stiffness_factor_;  // 2.25 μ_r²
};

}  // namespace granasym::dem
