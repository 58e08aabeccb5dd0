// Linear Cundall–Strack contact between elastic-frictional spheres, the
// paper's law and the default (SPEC §4).
//
//   k_n = 2E r_i r_j/(r_i + r_j),  k_s = ν k_n,  F_n = k_n u_N (repulsive),
//   F_s ← R F_s − k_s Δu_s,  |F_s| ≤ μ F_n
// (the tangential spring is IncrementalShearLaw, contact_law.h).
//
// Durations (paper Eq. 3): t_c = π / sqrt(k_n/m_12), independent of the
// impact speed; the stability limit uses the same k_n.
#pragma once

#include <cmath>
#include <string>

#include "common/state_measures.h"
#include "dem/contact_law.h"
#include "dem/material.h"

namespace granasym::dem {

class LinearCundallStrack : public IncrementalShearLaw<LinearCundallStrack> {
 public:
  static constexpr ContactLaw kContactLaw = ContactLaw::kLinear;
  // k_n does not depend on the overlap (the adaptive time step needs no pass
  // over the pairs).
  static constexpr bool kOverlapDependentStiffness = false;

  struct Params {
    double youngs_modulus = 500e6;      // E (Pa)
    double stiffness_ratio = 0.3;       // ν = k_s/k_n (Yade's "poisson")
    double friction_coefficient = 0.0;  // μ = tan φ; 0 keeps no shear history
    bool IsValid(std::string* why) const {
      if (!(youngs_modulus > 0)) return *why = "youngs_modulus must be > 0", false;
      if (!(stiffness_ratio >= 0)) return *why = "stiffness_ratio must be >= 0", false;
      if (!(friction_coefficient >= 0)) return *why = "friction_coefficient must be >= 0", false;
      return true;
    }
    // E is the material's contact modulus (its stiffness scaling applied).
    static Params FromMaterial(const Material& material) {
      return {material.contact_modulus(), material.stiffness_ratio,
              material.friction_coefficient()};
    }
  };
  // Compatibility names of the shared interface types.
  using Pair = ContactPair;
  using Result = ContactResult;
  using Batch = ContactBatch;

  LinearCundallStrack(const Params& params, double time_step)
      : params_(params), time_step_(time_step) {}

  // k_n, independent of the overlap (`distance` is not used) (N/m).
  double NormalStiffness(double radius_i, double radius_j, double distance = 0) const {
    return 2.0 * params_.youngs_modulus * radius_i * radius_j / (radius_i + radius_j);
  }

  // F_n = k_n u_N; reciprocal = 1/((r_i + r_j)|l|).
  GRANASYM_ALWAYS_INLINE NormalResponse Normal(double radius_i, double radius_j, double distance,
                                               double reciprocal, double overlap) const {
    const double k_n = 2.0 * params_.youngs_modulus * radius_i * radius_j * (distance * reciprocal);
    return {k_n * overlap, k_n};
  }
  double tangential_ratio() const { return params_.stiffness_ratio; }
  double friction_coefficient() const { return params_.friction_coefficient; }
  double time_step() const { return time_step_; }
  const Params& params() const { return params_; }

  // Undamped duration of a head-on contact of two spheres of radius r with the
  // effective mass m: π / sqrt(k_n/m), k_n = 2E r r/(2r) = E r (s).
  static double ImpactDuration(const Params& params, double radius, double mass) {
    const double k_n = params.youngs_modulus * radius;
    return kPi / std::sqrt(k_n / mass);
  }
  // The k_n of the stability limit (N/m).
  static double StabilityStiffness(const Params& params, double radius_i, double radius_j) {
    return 2.0 * params.youngs_modulus * radius_i * radius_j / (radius_i + radius_j);
  }
  static double TangentialStiffnessRatio(const Params& params) { return params.stiffness_ratio; }
  // κ = k_n/(d p) = E/(2p) at mean stress p > 0 (Pa) (k_n = E d/2 for equal
  // spheres; Material::StiffnessNumber).
  static double StiffnessNumber(const Params& params, double mean_stress) {
    return params.youngs_modulus / (2 * mean_stress);
  }
  static std::string StiffnessNumberDescription() { return "E/(2p) for the linear law"; }
  static std::string DurationDescription() {
    return "linear Cundall-Strack law: t_c = pi/sqrt(k_n/m_12), k_n = 2E r_i r_j/(r_i + r_j) "
           "(paper Eq. 3), independent of the impact speed; stability limit 2/omega_max with "
           "the same k_n";
  }

 private:
  Params params_;
  double time_step_;
};

}  // namespace granasym::dem
