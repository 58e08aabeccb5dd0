// Linear Cundall–Strack contact between elastic-frictional spheres (SPEC §4).
//
//   k_n = 2E r_i r_j/(r_i + r_j),  k_s = ν k_n,  F_n = k_n u_N (repulsive),
//   F_s ← R F_s − k_s Δu_s,  |F_s| ≤ μ F_n,
// where R rotates the stored shear force rigidly with the contact: the turn of
// the normal n over the step and the mean spin of the two spheres about n.
// The evaluator is a small struct plugged into the templated pair loop of
// ForceField (as HOOMD-blue's EvaluatorPair* into PotentialPair): the loop owns
// neighbours, images and accumulation; the law owns the physics of one pair.
#pragma once

#include <cmath>
#include <string>

#include "dem/vec.h"

namespace granasym::dem {

class LinearCundallStrack {
 public:
  struct Params {
    double youngs_modulus = 500e6;      // E (Pa)
    double stiffness_ratio = 0.3;       // ν = k_s/k_n (Yade's "poisson")
    double friction_coefficient = 0.0;  // μ = tan φ; 0 keeps no shear history
    bool IsValid(std::string* why) const;
  };

  // Kinematics of one pair at the current step. Sphere j is seen through the
  // image that makes `branch` (x_j + s − x_i) shortest.
  struct Pair {
    Vec3 branch;           // l (m)
    double distance;       // |l| (m)
    double radius_i, radius_j;
    Vec3 centre_velocity;  // v_j + L s − v_i: relative velocity of the centres (m/s)
    Vec3 spin_i, spin_j;   // angular velocities (rad/s)
  };

  // Result for sphere i; sphere j receives −force and its own torque.
  struct Result {
    Vec3 shear;         // updated shear force on i, to be stored (N)
    Vec3 force_i;       // total contact force on i (N)
    Vec3 torque_i;      // (N m)
    Vec3 torque_j;      // (N m)
    double normal_force;  // F_n (N), > 0
  };

  explicit LinearCundallStrack(const Params& params, double time_step)
      : params_(params), time_step_(time_step) {}

  double NormalStiffness(double radius_i, double radius_j) const {
    return 2.0 * params_.youngs_modulus * radius_i * radius_j / (radius_i + radius_j);
  }

  // Evaluates a pair in contact (overlap u_N = r_i + r_j − |l| > 0). With
  // kFriction the stored shear force `shear` (acting on i) is advanced and
  // returned in Result::shear, unless kFrozen: then the pair is re-evaluated
  // at the configuration of its last update with the stored force as it is.
  template <bool kFriction, bool kFrozen = false>
  inline Result Evaluate(const Pair& pair, Vec3 shear) const {
    const double reach = pair.radius_i + pair.radius_j;
    const double overlap = reach - pair.distance;
    // One division gives both 1/|l| and 1/(r_i + r_j).
    const double reciprocal = 1.0 / (reach * pair.distance);
    const double inverse_distance = reach * reciprocal;
    const Vec3 normal = inverse_distance * pair.branch;  // from i to j
    const double k_n =
        2.0 * params_.youngs_modulus * pair.radius_i * pair.radius_j * (pair.distance * reciprocal);
    Result result;
    result.shear = shear;
    result.normal_force = k_n * overlap;
    result.force_i = (-result.normal_force) * normal;
    if constexpr (kFriction && kFrozen) {
      const Vec3 moment = Cross(normal, shear);
      result.force_i = result.force_i + shear;
      result.torque_i = (pair.radius_i - 0.5 * overlap) * moment;
      result.torque_j = (pair.radius_j - 0.5 * overlap) * moment;
    } else if constexpr (kFriction) {
      const double arm_i = pair.radius_i - 0.5 * overlap;
      const double arm_j = pair.radius_j - 0.5 * overlap;
      // Rigid rotation of the contact over the step: the normal turned by
      // n × (Δt v_c)/|l| (the centres' relative motion that moved it) and the
      // frame spun about n by the mean spin.
      const double dt = time_step_;
      const Vec3 turn = (dt * inverse_distance) * Cross(normal, pair.centre_velocity);
      const Vec3 spin_sum = pair.spin_i + pair.spin_j;
      const Vec3 rotation = turn + (0.5 * dt * Dot(normal, spin_sum)) * normal;
      Vec3 force_s = shear;
      force_s = force_s + Cross(rotation, force_s);
      force_s = force_s - Dot(force_s, normal) * normal;
      // Relative velocity of j with respect to i at the contact point.
      const Vec3 contact_velocity =
          pair.centre_velocity - Cross(arm_i * pair.spin_i + arm_j * pair.spin_j, normal);
      const Vec3 tangential =
          contact_velocity - Dot(contact_velocity, normal) * normal;
      // j sliding by Δu_s relative to i drags i along: +k_s Δu_s on i.
      const double k_s = params_.stiffness_ratio * k_n;
      force_s = force_s + (k_s * dt) * tangential;
      const double limit = params_.friction_coefficient * result.normal_force;
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

  // A batch of touching pairs in structure-of-arrays form, evaluated by
  // EvaluateBatch in one loop that the compiler vectorises. Same physics as
  // Evaluate (tests compare the two); the Coulomb cap is branch-free.
  struct Batch {
    static constexpr int kSize = 128;
    // In: branch vector l, |l|², radii, centre velocity v_c, spins.
    double bx[kSize], by[kSize], bz[kSize], d2[kSize], ri[kSize], rj[kSize];
    double vx[kSize], vy[kSize], vz[kSize];
    double wix[kSize], wiy[kSize], wiz[kSize], wjx[kSize], wjy[kSize], wjz[kSize];
    // In and out: the stored shear force on i.
    double sx[kSize], sy[kSize], sz[kSize];
    // Out: force on i, torques on i and j.
    double fx[kSize], fy[kSize], fz[kSize];
    double tix[kSize], tiy[kSize], tiz[kSize], tjx[kSize], tjy[kSize], tjz[kSize];
  };

  template <bool kFriction>
  void EvaluateBatch(Batch& b, int count) const {
    const double two_e = 2.0 * params_.youngs_modulus;
    const double ratio = params_.stiffness_ratio;
    const double mu = params_.friction_coefficient;
    const double dt = time_step_;
#pragma omp simd
    for (int k = 0; k < count; ++k) {
      const double distance = std::sqrt(b.d2[k]);
      const double reach = b.ri[k] + b.rj[k];
      const double overlap = reach - distance;
      const double reciprocal = 1.0 / (reach * distance);
      const double inverse_distance = reach * reciprocal;
      const double nx = inverse_distance * b.bx[k];
      const double ny = inverse_distance * b.by[k];
      const double nz = inverse_distance * b.bz[k];
      const double k_n = two_e * b.ri[k] * b.rj[k] * (distance * reciprocal);
      const double normal_force = k_n * overlap;
      double fx = -normal_force * nx, fy = -normal_force * ny, fz = -normal_force * nz;
      if constexpr (kFriction) {
        const double arm_i = b.ri[k] - 0.5 * overlap;
        const double arm_j = b.rj[k] - 0.5 * overlap;
        const double vx = b.vx[k], vy = b.vy[k], vz = b.vz[k];
        // Rotation vector: turn of the normal, n × (Δt v_c)/|l|, plus the
        // mean spin about n.
        const double scale = dt * inverse_distance;
        const double spin_n = 0.5 * dt *
                              (nx * (b.wix[k] + b.wjx[k]) + ny * (b.wiy[k] + b.wjy[k]) +
                               nz * (b.wiz[k] + b.wjz[k]));
        const double rx = scale * (ny * vz - nz * vy) + spin_n * nx;
        const double ry = scale * (nz * vx - nx * vz) + spin_n * ny;
        const double rz = scale * (nx * vy - ny * vx) + spin_n * nz;
        double sx = b.sx[k], sy = b.sy[k], sz = b.sz[k];
        const double ux = sx + (ry * sz - rz * sy);
        const double uy = sy + (rz * sx - rx * sz);
        const double uz = sz + (rx * sy - ry * sx);
        const double un = ux * nx + uy * ny + uz * nz;
        sx = ux - un * nx;
        sy = uy - un * ny;
        sz = uz - un * nz;
        // Relative velocity at the contact point, tangential part.
        const double ax = arm_i * b.wix[k] + arm_j * b.wjx[k];
        const double ay = arm_i * b.wiy[k] + arm_j * b.wjy[k];
        const double az = arm_i * b.wiz[k] + arm_j * b.wjz[k];
        const double cx = vx - (ay * nz - az * ny);
        const double cy = vy - (az * nx - ax * nz);
        const double cz = vz - (ax * ny - ay * nx);
        const double cn = cx * nx + cy * ny + cz * nz;
        const double k_s_dt = ratio * k_n * dt;
        sx += k_s_dt * (cx - cn * nx);
        sy += k_s_dt * (cy - cn * ny);
        sz += k_s_dt * (cz - cn * nz);
        // Coulomb cap without a branch: the factor is exactly 1 below the
        // limit (and for a zero force, where the quotient is inf or NaN and
        // the comparison keeps 1).
        const double limit = mu * normal_force;
        const double magnitude = std::sqrt(sx * sx + sy * sy + sz * sz);
        const double quotient = limit / magnitude;
        const double cap = quotient < 1.0 ? quotient : 1.0;
        sx *= cap;
        sy *= cap;
        sz *= cap;
        b.sx[k] = sx;
        b.sy[k] = sy;
        b.sz[k] = sz;
        fx += sx;
        fy += sy;
        fz += sz;
        const double mx = ny * sz - nz * sy, my = nz * sx - nx * sz, mz = nx * sy - ny * sx;
        b.tix[k] = arm_i * mx;
        b.tiy[k] = arm_i * my;
        b.tiz[k] = arm_i * mz;
        b.tjx[k] = arm_j * mx;
        b.tjy[k] = arm_j * my;
        b.tjz[k] = arm_j * mz;
      }
      b.fx[k] = fx;
      b.fy[k] = fy;
      b.fz[k] = fz;
    }
  }

  const Params& params() const { return params_; }
  double time_step() const { return time_step_; }

 private:
  Params params_;
  double time_step_;
};

}  // namespace granasym::dem
