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

  const Params& params() const { return params_; }
  double time_step() const { return time_step_; }

 private:
  Params params_;
  double time_step_;
};

}  // namespace granasym::dem
