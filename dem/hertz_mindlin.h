// Hertz–Mindlin contact between spheres of one elastic-frictional material
// (SPEC §8.1).
//
//   E* = E/(2(1 − ν²)),  G* = G/(2(2 − ν)),  G = E/(2(1 + ν)),  R* = r_i r_j/(r_i + r_j),
//   F_n = (4/3) E* √R* u_N^{3/2},  k_n = dF_n/du_N = 2 E* √(R* u_N),
//   k_t = 8 G* √(R* u_N) = (4G*/E*) k_n = 2(1 − ν)/(2 − ν) k_n  (no-slip Mindlin),
// with k_t used incrementally exactly as the linear law's k_s (the stored
// force is rotated with the contact and incremented by k_t Δt v_t, then capped
// at μ F_n; IncrementalShearLaw, contact_law.h). The stored force is not
// rescaled when k_t changes with the overlap (codes that store the tangential
// displacement instead rescale it implicitly): a loading–unloading cycle with
// shear can then release slightly more or less energy than it stored.
//
// Durations. A Hertz contact has no overlap-independent duration:
//   t_c = 2.868 (m*²/(R* E*² v))^{1/5}  at normal impact speed v
// (2.868 = 2.9433 (15/16)^{2/5}; SPEC rounds it to 2.87). The duration fields
// of ContactDurations use the reference speed kReferenceImpactSpeed = 1 m/s
// (neighbours at ‖D‖ = 167 1/s approach at about ‖D‖ d ≤ 0.2 m/s, and their
// contacts last 1.4 times longer: the reference is on the safe side). The stability
// limit uses the stiffness k_n at the relative overlap
// u_N/(r_i + r_j) = kStabilityRelativeOverlap = 0.1, the overlap beyond which
// results are unreliable anyway (SPEC §8.3); a contact overlapping less is
// softer, so a step below that limit is stable for every reliable state.
#pragma once

#include <cmath>
#include <string>

#include "dem/contact_law.h"
#include "dem/material.h"

namespace granasym::dem {

class HertzMindlin : public IncrementalShearLaw<HertzMindlin> {
 public:
  static constexpr ContactLaw kContactLaw = ContactLaw::kHertzMindlin;
  // k_n = 2E* sqrt(R* u_N) grows with the overlap (the adaptive time step
  // follows it over the touching pairs).
  static constexpr bool kOverlapDependentStiffness = true;

  struct Params {
    double youngs_modulus = 500e6;      // E (Pa)
    double poissons_ratio = 0.25;       // ν, in (−1, 0.5)
    double friction_coefficient = 0.0;  // μ = tan φ; 0 keeps no shear history
    bool IsValid(std::string* why) const {
      if (!(youngs_modulus > 0)) return *why = "youngs_modulus must be > 0", false;
      if (!(poissons_ratio > -1 && poissons_ratio < 0.5)) {
        return *why = "poissons_ratio must be in (-1, 0.5)", false;
      }
      if (!(friction_coefficient >= 0)) return *why = "friction_coefficient must be >= 0", false;
      return true;
    }
    // E is the material's contact modulus (its stiffness scaling applied).
    static Params FromMaterial(const Material& material) {
      return {material.contact_modulus(), material.poissons_ratio, material.friction_coefficient()};
    }
    // E* (Pa).
    double effective_modulus() const {
      return youngs_modulus / (2.0 * (1.0 - poissons_ratio * poissons_ratio));
    }
    // G* (Pa).
    double effective_shear_modulus() const {
      const double shear_modulus = youngs_modulus / (2.0 * (1.0 + poissons_ratio));
      return shear_modulus / (2.0 * (2.0 - poissons_ratio));
    }
  };

  static constexpr double kReferenceImpactSpeed = 1.0;      // m/s, for the duration fields
  static constexpr double kStabilityRelativeOverlap = 0.1;  // u_N/(r_i + r_j) of the limit
  static constexpr double kDurationFactor = 2.8682657;      // t_c = 2.868 (m*²/(R* E*² v))^{1/5}

  HertzMindlin(const Params& params, double time_step)
      : params_(params),
        time_step_(time_step),
        two_effective_modulus_(2.0 * params.effective_modulus()),
        tangential_ratio_(TangentialStiffnessRatio(params)) {}

  // k_n = 2 E* √(R* u_N) at the overlap of centres `distance` apart (N/m).
  double NormalStiffness(double radius_i, double radius_j, double distance) const {
    const double overlap = radius_i + radius_j - distance;
    const double reduced_radius = radius_i * radius_j / (radius_i + radius_j);
    return two_effective_modulus_ * std::sqrt(reduced_radius * (overlap > 0 ? overlap : 0.0));
  }

  // F_n = (2/3) k_n u_N; reciprocal = 1/((r_i + r_j)|l|). A touching pair
  // can round to u_N = −1 ulp: clamped, so that the root stays real.
  GRANASYM_ALWAYS_INLINE NormalResponse Normal(double radius_i, double radius_j, double distance,
                                               double reciprocal, double overlap) const {
    const double reduced_radius = radius_i * radius_j * (distance * reciprocal);
    const double u = overlap > 0 ? overlap : 0.0;
    const double k_n = two_effective_modulus_ * std::sqrt(reduced_radius * u);
    return {(2.0 / 3.0) * k_n * u, k_n};
  }
  double tangential_ratio() const { return tangential_ratio_; }
  double friction_coefficient() const { return params_.friction_coefficient; }
  double time_step() const { return time_step_; }
  const Params& params() const { return params_; }

  // Hertz duration of a head-on impact at kReferenceImpactSpeed of two spheres
  // of radius r (R* = r/2) with the effective mass m (s).
  static double ImpactDuration(const Params& params, double radius, double mass) {
    return ImpactDurationAtSpeed(params, radius, mass, kReferenceImpactSpeed);
  }
  static double ImpactDurationAtSpeed(const Params& params, double radius, double mass,
                                      double speed) {
    const double reduced_radius = 0.5 * radius;
    const double modulus = params.effective_modulus();
    return kDurationFactor *
           std::pow(mass * mass / (reduced_radius * modulus * modulus * speed), 0.2);
  }
  // k_n at the relative overlap kStabilityRelativeOverlap (N/m).
  static double StabilityStiffness(const Params& params, double radius_i, double radius_j) {
    const double reduced_radius = radius_i * radius_j / (radius_i + radius_j);
    const double overlap = kStabilityRelativeOverlap * (radius_i + radius_j);
    return 2.0 * params.effective_modulus() * std::sqrt(reduced_radius * overlap);
  }
  // k_t/k_n = 4 G*/E* = 2(1 − ν)/(2 − ν).
  static double TangentialStiffnessRatio(const Params& params) {
    return 4.0 * params.effective_shear_modulus() / params.effective_modulus();
  }
  // κ = (E*/p)^(2/3) at mean stress p > 0 (Pa) (Material::StiffnessNumber).
  static double StiffnessNumber(const Params& params, double mean_stress) {
    return std::pow(params.effective_modulus() / mean_stress, 2.0 / 3.0);
  }
  static std::string StiffnessNumberDescription() { return "(E*/p)^(2/3) for Hertz-Mindlin"; }
  static std::string DurationDescription() {
    return "Hertz-Mindlin law: t_c = 2.868 (m_12^2/(R* E*^2 v))^(1/5) at the reference normal "
           "impact speed v = 1 m/s (slower impacts last longer); stability limit 2/omega_max "
           "with k_n = 2E* sqrt(R* u_N) at the relative overlap u_N/(r_i + r_j) = 0.1";
  }

 private:
  Params params_;
  double time_step_;
  double two_effective_modulus_;  // 2E* (Pa)
  double tangential_ratio_;       // k_t/k_n
};

}  // namespace granasym::dem
