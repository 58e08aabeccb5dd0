// The interface between the DEM pair loop and its contact laws, and the
// incremental tangential spring that the laws share (SPEC §4, §8.1).
//
// A contact law is a small evaluator class plugged into the templated pair
// loop of Engine (engine.cc), as HOOMD-blue's EvaluatorPair* into
// PotentialPair: the loop owns neighbours, periodic images, the per-pair
// history, accumulation of forces and torques, and the sums; the law owns the
// physics of one pair. A law `Law` provides
//   Law::Params                       parameters: IsValid(why), FromMaterial(material)
//   Law(params, time_step)
//   Law::kRollingHistory              true when it carries a rolling moment per pair
//   Evaluate<kFriction, kFrozen>(pair, history) -> ContactResult
//                                     the scalar reference evaluation of one pair
//   EvaluateBatch<kFriction>(batch, count)
//                                     the same physics on a ContactBatch in one
//                                     vectorised loop: the fast path
//   NormalStiffness(r_i, r_j, |l|)    tangent normal stiffness dF_n/du_N (N/m), for
//                                     the affine stiffness sums (Engine::Sums)
// and static members that state its contact duration and stability limit
// (ImpactDuration, StabilityStiffness, TangentialStiffnessRatio,
// DurationDescription), from which ComputeContactDurations (material.h) builds
// the time-step check, whether k_n depends on the overlap
// (kOverlapDependentStiffness: the adaptive time step's pass over the pairs)
// and the stiffness number κ at a mean stress (StiffnessNumber, with its
// StiffnessNumberDescription). A normal law names its ContactLaw value
// (kContactLaw) and is listed in contact_laws.h.
//
// The normal laws (linear_cundall_strack.h, hertz_mindlin.h) differ only in
// the normal force F_n(u_N) and its stiffness k_n, and in the ratio k_t/k_n of
// the tangential stiffness; IncrementalShearLaw below writes the rest once:
//   F_s ← R F_s + k_t Δt v_t,  |F_s| ≤ μ F_n,
// where R rotates the stored shear force rigidly with the contact (the turn of
// the normal n over the step and the mean spin of the two spheres about n) and
// v_t is the tangential relative velocity of j with respect to i at the
// contact point. Rolling resistance (rolling_resistance.h) decorates either.
#pragma once

#include <cmath>
#include <cstdint>

#include "dem/vec.h"

#if defined(__GNUC__)
#define GRANASYM_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define GRANASYM_ALWAYS_INLINE inline
#endif

namespace granasym::dem {

// Kinematics of one pair at the current step. Sphere j is seen through the
// image that makes `branch` (x_j + s − x_i) shortest.
struct ContactPair {
  Vec3 branch;      // l (m)
  double distance;  // |l| (m)
  double radius_i, radius_j;
  Vec3 centre_velocity;  // v_j + L s − v_i: relative velocity of the centres (m/s)
  Vec3 spin_i, spin_j;   // angular velocities (rad/s)
};

// What a pair remembers between steps (stored by the neighbour list).
struct ContactHistory {
  Vec3 shear{};    // tangential force on i (N)
  Vec3 rolling{};  // rolling moment on i (N m); only laws with kRollingHistory
};

// Result for sphere i; sphere j receives −force_i and torque_j.
struct ContactResult {
  Vec3 shear;           // updated shear force on i, to be stored (N)
  Vec3 rolling;         // updated rolling moment on i, to be stored (N m)
  Vec3 force_i;         // total contact force on i (N)
  Vec3 torque_i;        // (N m)
  Vec3 torque_j;        // (N m)
  double normal_force;  // F_n (N), >= 0
};

// A batch of touching pairs in structure-of-arrays form, evaluated by a law's
// EvaluateBatch in one loop that the compiler vectorises.
struct ContactBatch {
  static constexpr int kSize = 128;
  // In: branch vector l, |l|², radii, centre velocity v_c, spins.
  double bx[kSize], by[kSize], bz[kSize], d2[kSize], ri[kSize], rj[kSize];
  double vx[kSize], vy[kSize], vz[kSize];
  double wix[kSize], wiy[kSize], wiz[kSize], wjx[kSize], wjy[kSize], wjz[kSize];
  // In and out: the stored shear force on i, and (rolling resistance only)
  // the stored rolling moment on i.
  double sx[kSize], sy[kSize], sz[kSize];
  double rmx[kSize], rmy[kSize], rmz[kSize];
  // Out: force on i, torques on i and j.
  double fx[kSize], fy[kSize], fz[kSize];
  double tix[kSize], tiy[kSize], tiz[kSize], tjx[kSize], tjy[kSize], tjz[kSize];
  // Scratch of IncrementalShearLaw::EvaluateBatch: 1 where the Coulomb cap
  // may act (the lane is finished by its second loop), else 0.
  int64_t capped[kSize];
};

// Normal force and tangent stiffness of a normal law at one overlap.
struct NormalResponse {
  double force;      // F_n (N)
  double stiffness;  // k_n = dF_n/du_N (N/m)
};

// Rotation vector of the contact frame over one step: the normal turned by
// n × (Δt v_c)/|l| (the centres' relative motion that moved it) and the
// frame spun about n by the mean spin.
inline Vec3 ContactRotation(const ContactPair& pair, Vec3 normal, double inverse_distance,
                            double dt) {
  const Vec3 turn = (dt * inverse_distance) * Cross(normal, pair.centre_velocity);
  const Vec3 spin_sum = pair.spin_i + pair.spin_j;
  return turn + (0.5 * dt * Dot(normal, spin_sum)) * normal;
}

// A stored tangential vector carried with the contact: rotated by `rotation`
// (first order) and projected back onto the current tangent plane.
inline Vec3 CarryWithContact(Vec3 stored, Vec3 rotation, Vec3 normal) {
  stored = stored + Cross(rotation, stored);
  return stored - Dot(stored, normal) * normal;
}

// The geometry of lane k of a batch: |l|, the overlap u_N, 1/((r_i + r_j)|l|)
// (one division gives both 1/|l| and 1/(r_i + r_j)), 1/|l| and the normal n.
struct LaneGeometry {
  double distance, overlap, reciprocal, inverse_distance, nx, ny, nz;
};
GRANASYM_ALWAYS_INLINE LaneGeometry ContactGeometryLane(const ContactBatch& b, int k) {
  LaneGeometry g;
  g.distance = std::sqrt(b.d2[k]);
  const double reach = b.ri[k] + b.rj[k];
  g.overlap = reach - g.distance;
  g.reciprocal = 1.0 / (reach * g.distance);
  g.inverse_distance = reach * g.reciprocal;
  g.nx = g.inverse_distance * b.bx[k];
  g.ny = g.inverse_distance * b.by[k];
  g.nz = g.inverse_distance * b.bz[k];
  return g;
}

// One lane of ContactRotation for the batch loops (b.bx.. are not read:
// n and 1/|l| come from the caller).
GRANASYM_ALWAYS_INLINE void ContactRotationLane(const ContactBatch& b, int k, double nx, double ny,
                                                double nz, double inverse_distance, double dt,
                                                double& rx, double& ry, double& rz) {
  const double scale = dt * inverse_distance;
  const double spin_n =
      0.5 * dt *
      (nx * (b.wix[k] + b.wjx[k]) + ny * (b.wiy[k] + b.wjy[k]) + nz * (b.wiz[k] + b.wjz[k]));
  const double vx = b.vx[k], vy = b.vy[k], vz = b.vz[k];
  rx = scale * (ny * vz - nz * vy) + spin_n * nx;
  ry = scale * (nz * vx - nx * vz) + spin_n * ny;
  rz = scale * (nx * vy - ny * vx) + spin_n * nz;
}

// One lane of CarryWithContact: (x, y, z) rotated by (rx, ry, rz) and
// projected back onto the plane normal to (nx, ny, nz).
GRANASYM_ALWAYS_INLINE void CarryWithContactLane(double rx, double ry, double rz, double nx,
                                                 double ny, double nz, double& x, double& y,
                                                 double& z) {
  const double ux = x + (ry * z - rz * y);
  const double uy = y + (rz * x - rx * z);
  const double uz = z + (rx * y - ry * x);
  const double un = ux * nx + uy * ny + uz * nz;
  x = ux - un * nx;
  y = uy - un * ny;
  z = uz - un * nz;
}

// The Coulomb-type cap of one lane without a branch: (x, y, z) scaled by
// min(limit/|(x, y, z)|, 1), exactly 1 below the limit (and for a zero
// vector, where the quotient is inf or NaN and the comparison keeps 1).
GRANASYM_ALWAYS_INLINE void CapLane(double limit, double& x, double& y, double& z) {
  const double magnitude = std::sqrt(x * x + y * y + z * z);
  const double quotient = limit / magnitude;
  const double cap = quotient < 1.0 ? quotient : 1.0;
  x *= cap;
  y *= cap;
  z *= cap;
}

// The laws whose tangential force is the incremental spring of SPEC §4 with a
// Coulomb cap. `Law` (CRTP) provides
//   NormalResponse Normal(r_i, r_j, |l|, reciprocal, u_N) const
//     with reciprocal = 1/((r_i + r_j)|l|), so that |l|·reciprocal = 1/(r_i + r_j);
//   double tangential_ratio() const        k_t/k_n;
//   double friction_coefficient() const    μ;
//   double time_step() const               Δt (s).
template <class Law>
class IncrementalShearLaw {
 public:
  static constexpr bool kRollingHistory = false;

  // Evaluates a pair in contact (overlap u_N = r_i + r_j − |l| > 0). With
  // kFriction the stored shear force history.shear (acting on i) is advanced
  // and returned in ContactResult::shear, unless kFrozen: then the pair is
  // re-evaluated at the configuration of its last update with the stored
  // force as it is.
  template <bool kFriction, bool kFrozen = false>
  ContactResult Evaluate(const ContactPair& pair, const ContactHistory& history) const {
    const Law& law = static_cast<const Law&>(*this);
    const double reach = pair.radius_i + pair.radius_j;
    const double overlap = reach - pair.distance;
    // One division gives both 1/|l| and 1/(r_i + r_j).
    const double reciprocal = 1.0 / (reach * pair.distance);
    const double inverse_distance = reach * reciprocal;
    const Vec3 normal = inverse_distance * pair.branch;  // from i to j
    const NormalResponse response =
        law.Normal(pair.radius_i, pair.radius_j, pair.distance, reciprocal, overlap);
    ContactResult result;
    result.shear = history.shear;
    result.rolling = history.rolling;
    result.normal_force = response.force;
    result.force_i = (-result.normal_force) * normal;
    result.torque_i = result.torque_j = Vec3{};
    if constexpr (kFriction && kFrozen) {
      const Vec3 moment = Cross(normal, history.shear);
      result.force_i = result.force_i + history.shear;
      result.torque_i = (pair.radius_i - 0.5 * overlap) * moment;
      result.torque_j = (pair.radius_j - 0.5 * overlap) * moment;
    } else if constexpr (kFriction) {
      const double arm_i = pair.radius_i - 0.5 * overlap;
      const double arm_j = pair.radius_j - 0.5 * overlap;
      const double dt = law.time_step();
      const Vec3 rotation = ContactRotation(pair, normal, inverse_distance, dt);
      Vec3 force_s = CarryWithContact(history.shear, rotation, normal);
      // Relative velocity of j with respect to i at the contact point.
      const Vec3 contact_velocity =
          pair.centre_velocity - Cross(arm_i * pair.spin_i + arm_j * pair.spin_j, normal);
      const Vec3 tangential = contact_velocity - Dot(contact_velocity, normal) * normal;
      // j sliding by Δu_s relative to i drags i along: +k_t Δu_s on i.
      const double k_t = law.tangential_ratio() * response.stiffness;
      force_s = force_s + (k_t * dt) * tangential;
      const double limit = law.friction_coefficient() * result.normal_force;
      const double magnitude2 = Dot(force_s, force_s);
      if (magnitude2 > limit * limit) force_s = (limit / std::sqrt(magnitude2)) * force_s;
      result.shear = force_s;
      result.force_i = result.force_i + force_s;
      const Vec3 moment = Cross(normal, force_s);
      result.torque_i = arm_i * moment;
      result.torque_j = arm_j * moment;
    }
    return result;
  }

  // Same physics as Evaluate (tests compare the two) on `count` pairs of `b`.
  // The Coulomb cap costs a square root and a division per pair, the dearest
  // operations of the law, yet acts only on the sliding contacts, usually a
  // small share. The first, vectorised loop therefore finishes every pair as
  // if the cap were 1 and marks the pairs where it may not be: those whose
  // |F_s|² is not clearly below (μ F_n)² (or not a number). A second, scalar
  // loop finishes the marked pairs with the cap as Evaluate computes it. The
  // mark is conservative: an unmarked pair's |F_s| rounds below μ F_n, so
  // the quotient μ F_n/|F_s| would round to at least 1 and the cap to
  // exactly 1, and both loops compute every value by the same operations in
  // the same order (no contraction), so the results are those of one loop
  // with the cap everywhere, bit for bit.
  template <bool kFriction>
  void EvaluateBatch(ContactBatch& b, int count) const {
    const Law& law = static_cast<const Law&>(*this);
    const double ratio = law.tangential_ratio();
    const double mu = law.friction_coefficient();
    const double dt = law.time_step();
    // Below 1 by far more than the rounding of |F_s| and (μ F_n)²; limits
    // under 1e-150 N (whose square may be subnormal and lose its relative
    // precision) are always marked.
    constexpr double kClearlyBelow = 1.0 - 0x1p-20;
    constexpr double kSmallestLimit = 1e-150;
#pragma omp simd
    for (int k = 0; k < count; ++k) {
      const ShearLane lane = AdvanceShearLane<kFriction>(law, b, k, ratio, dt);
      if constexpr (kFriction) {
        const double sx = lane.sx, sy = lane.sy, sz = lane.sz;
        const double limit = mu * lane.normal_force;
        const double magnitude2 = sx * sx + sy * sy + sz * sz;
        const bool below = magnitude2 <= kClearlyBelow * (limit * limit) && limit > kSmallestLimit;
        b.capped[k] = below ? 0 : 1;
        FinishShearLane(b, k, lane, sx, sy, sz);
      } else {
        b.fx[k] = -lane.normal_force * lane.nx;
        b.fy[k] = -lane.normal_force * lane.ny;
        b.fz[k] = -lane.normal_force * lane.nz;
      }
    }
    if constexpr (kFriction) {
      // The marked pairs, compacted (a loop over all pairs with a skip would
      // be vectorised with the skip as a mask: the cap for every pair again).
      int marked[ContactBatch::kSize];
      int marked_count = 0;
      for (int k = 0; k < count; ++k) {
        marked[marked_count] = k;
        marked_count += static_cast<int>(b.capped[k]);
      }
      for (int q = 0; q < marked_count; ++q) {
        const int k = marked[q];
        // b.sx.. now hold this pair's shear force before the cap; the lane's
        // geometry and normal force again, by the same operations.
        const ShearLane lane = NormalLane(law, b, k);
        double sx = b.sx[k], sy = b.sy[k], sz = b.sz[k];
        CapLane(mu * lane.normal_force, sx, sy, sz);
        FinishShearLane(b, k, lane, sx, sy, sz);
      }
    }
  }

 private:
  // One pair of a batch up to its shear force before the Coulomb cap.
  struct ShearLane {
    double nx, ny, nz, inverse_distance, normal_force, normal_stiffness, arm_i, arm_j;
    double sx, sy, sz;  // the stored shear force carried and incremented (kFriction)
  };
  // Its geometry, normal force and lever arms.
  static GRANASYM_ALWAYS_INLINE ShearLane NormalLane(const Law& law, const ContactBatch& b, int k) {
    ShearLane lane;
    const LaneGeometry g = ContactGeometryLane(b, k);
    const NormalResponse response =
        law.Normal(b.ri[k], b.rj[k], g.distance, g.reciprocal, g.overlap);
    lane.inverse_distance = g.inverse_distance;
    lane.nx = g.nx;
    lane.ny = g.ny;
    lane.nz = g.nz;
    lane.normal_force = response.force;
    lane.normal_stiffness = response.stiffness;
    lane.arm_i = b.ri[k] - 0.5 * g.overlap;
    lane.arm_j = b.rj[k] - 0.5 * g.overlap;
    return lane;
  }
  template <bool kFriction>
  static GRANASYM_ALWAYS_INLINE ShearLane AdvanceShearLane(const Law& law, const ContactBatch& b,
                                                           int k, double ratio, double dt) {
    ShearLane lane = NormalLane(law, b, k);
    const double nx = lane.nx, ny = lane.ny, nz = lane.nz;
    if constexpr (kFriction) {
      const double arm_i = lane.arm_i, arm_j = lane.arm_j;
      const double vx = b.vx[k], vy = b.vy[k], vz = b.vz[k];
      double rx, ry, rz;
      ContactRotationLane(b, k, nx, ny, nz, lane.inverse_distance, dt, rx, ry, rz);
      double sx = b.sx[k], sy = b.sy[k], sz = b.sz[k];
      CarryWithContactLane(rx, ry, rz, nx, ny, nz, sx, sy, sz);
      // Relative velocity at the contact point, tangential part.
      const double ax = arm_i * b.wix[k] + arm_j * b.wjx[k];
      const double ay = arm_i * b.wiy[k] + arm_j * b.wjy[k];
      const double az = arm_i * b.wiz[k] + arm_j * b.wjz[k];
      const double cx = vx - (ay * nz - az * ny);
      const double cy = vy - (az * nx - ax * nz);
      const double cz = vz - (ax * ny - ay * nx);
      const double cn = cx * nx + cy * ny + cz * nz;
      const double k_t_dt = ratio * lane.normal_stiffness * dt;
      sx += k_t_dt * (cx - cn * nx);
      sy += k_t_dt * (cy - cn * ny);
      sz += k_t_dt * (cz - cn * nz);
      lane.sx = sx;
      lane.sy = sy;
      lane.sz = sz;
    }
    return lane;
  }
  // Stores the (capped) shear force (sx, sy, sz), the force on i (normal
  // plus shear) and the torques of pair k.
  static GRANASYM_ALWAYS_INLINE void FinishShearLane(ContactBatch& b, int k, const ShearLane& lane,
                                                     double sx, double sy, double sz) {
    b.sx[k] = sx;
    b.sy[k] = sy;
    b.sz[k] = sz;
    double fx = -lane.normal_force * lane.nx, fy = -lane.normal_force * lane.ny,
           fz = -lane.normal_force * lane.nz;
    fx += sx;
    fy += sy;
    fz += sz;
    const double nx = lane.nx, ny = lane.ny, nz = lane.nz;
    const double mx = ny * sz - nz * sy, my = nz * sx - nx * sz, mz = nx * sy - ny * sx;
    b.tix[k] = lane.arm_i * mx;
    b.tiy[k] = lane.arm_i * my;
    b.tiz[k] = lane.arm_i * mz;
    b.tjx[k] = lane.arm_j * mx;
    b.tjy[k] = lane.arm_j * my;
    b.tjz[k] = lane.arm_j * mz;
    b.fx[k] = fx;
    b.fy[k] = fy;
    b.fz[k] = fz;
  }
};

}  // namespace granasym::dem
