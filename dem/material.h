// The grain material of a DEM scene: which contact law, its parameters, and
// the contact durations and stability limit that the time step is checked
// against (SPEC §4, §8.1).
//
// The paper's linear Cundall–Strack law is the default; Hertz–Mindlin is the
// alternative normal law, and rolling resistance (Ai et al. 2011) can be
// added to either. Each law states its own durations (ImpactDuration and
// StabilityStiffness in its header); ComputeContactDurations assembles them
// for a set of radii.
#pragma once

#include <string>
#include <vector>

#include "common/enum_names.h"

namespace granasym {
class CanonicalText;
class ConfigTable;
}  // namespace granasym

namespace granasym::dem {

enum class ContactLaw { kLinear, kHertzMindlin };
}  // namespace granasym::dem

template <>
struct granasym::EnumNames<granasym::dem::ContactLaw> {
  static constexpr EnumEntry<dem::ContactLaw> kEntries[] = {
      {dem::ContactLaw::kLinear, "linear", "linear Cundall-Strack (the paper's law)"},
      {dem::ContactLaw::kHertzMindlin, "hertz_mindlin", "Hertz normal, no-slip Mindlin tangential"},
  };
};

namespace granasym::dem {
using granasym::FromString;
using granasym::ToString;

struct Material {
  // Normal and tangential law of a contact.
  ContactLaw contact_law = ContactLaw::kLinear;
  double youngs_modulus = 500e6;  // E (Pa)
  // Linear law only: ν = k_s/k_n (Yade calls it the material's "poisson").
  double stiffness_ratio = 0.3;
  // Hertz–Mindlin only: Poisson's ratio ν of the grain material, in (−1, 0.5).
  double poissons_ratio = 0.25;
  double friction_angle = 0.5;  // φ (rad); μ = tan φ
  // μ_r of the rolling resistance (dimensionless); 0 switches it off. Needs
  // friction (without tangential forces no sphere spins).
  double rolling_friction = 0.0;
  double density = 2650.0;     // ρ_s (kg/m³)
  double local_damping = 0.5;  // χ in [0, 1)
  // Stiffness scaling s in (0, 1]: the contact laws use the modulus s·E
  // (contact_modulus()). Softer contacts last longer (t_c ∝ 1/sqrt(E) for the
  // linear law), so an adaptive time step grows by 1/sqrt(s) and the steps per
  // unit strain at a given inertial number fall by sqrt(s) (SPEC §8.2); the
  // stiffness number κ falls with it (by s for the linear law, s^(2/3) for
  // Hertz–Mindlin), so its effect on a result must be measured.
  double stiffness_scaling = 1.0;

  // The Young's modulus the contact laws use: s·E (Pa).
  double contact_modulus() const { return stiffness_scaling * youngs_modulus; }

  // Names the offending field in `why`.
  bool IsValid(std::string* why) const;
  // Tangential forces, torques and spins are computed (μ > 0 and, for the
  // linear law, k_s > 0).
  bool has_friction() const;
  bool has_rolling_resistance() const { return rolling_friction > 0; }
  double friction_coefficient() const;  // μ = tan φ
  // The stiffness number κ at mean stress p (Pa): the inverse of the typical
  // overlap relative to the diameter (Agnolin & Roux 2007; SPEC §8.2), as
  // the law defines it (Law::StiffnessNumber): the linear law κ = k_n/(d p) =
  // E/(2p) (k_n = E d/2 for equal spheres), Hertz–Mindlin κ = (E*/p)^(2/3),
  // E* = E/(2(1 − ν²)), with E the contact modulus (the stiffness scaling
  // applied); +inf where p ≤ 0.
  double StiffnessNumber(double mean_stress) const;
  // The keys of its own law only, as ParseMaterial reads them (`prefix`
  // ends with '.' or is empty).
  void Canonical(CanonicalText& text, const std::string& prefix) const;
};

// Reads a [material] table. Keys and units: contact_law ("linear" or
// "hertz_mindlin", default "linear"), youngs_modulus_mpa, stiffness_ratio
// (linear only), poissons_ratio (hertz_mindlin only), friction_angle_rad,
// rolling_friction, density_kg_m3, local_damping, stiffness_scaling; each
// defaults to Material's value. A key of the other law, a value out of range,
// an unknown key or rolling resistance without friction is an InputError
// naming the key, the value and what is valid.
Material ParseMaterial(const ConfigTable& table);

// Contact durations and the leapfrog stability limit of the material's law
// for the smallest and largest spheres, with both mass conventions of SPEC §4
// (the reduced mass m_12 = m_i m_j/(m_i + m_j) of two equal spheres, and one
// sphere's mass m, the paper's quoted values). For the linear law these are
// t_c = π / sqrt(k_n/m_12) (paper Eq. 3); for Hertz–Mindlin, whose duration
// depends on the impact speed, the Hertz duration at a reference speed (see
// hertz_mindlin.h). `description` says how the numbers were computed.
struct ContactDurations {
  double smallest_reduced_mass = 0;  // two smallest spheres, m_12 (s)
  double largest_reduced_mass = 0;   // two largest spheres, m_12 (s)
  double smallest_single_mass = 0;   // two smallest spheres, m_12 = m (s)
  double largest_single_mass = 0;    // two largest spheres, m_12 = m (s)
  // Stability limit of the leapfrog scheme for the stiffest pair (the two
  // smallest spheres), 2/ω_max, ω_max² = k_n (1/m_i + 1/m_j) times the
  // larger of 1, 3.5 k_t/k_n (with friction: sliding couples with rolling,
  // 3.5 = 1 + r²m/I) and, with rolling resistance, k_r (1/I_i + 1/I_j) /
  // (k_n (1/m_i + 1/m_j)). k_n is the law's StabilityStiffness (s).
  double critical_time_step = 0;
  // The largest stable Δt as a fraction of a pair's undamped duration at the
  // same tangent stiffness, critical / (π sqrt(m_12/k_n)) = 2/(π sqrt(factor))
  // with the factor above (two smallest spheres): independent of k_n, so for
  // Hertz–Mindlin it holds at every overlap. The bound of an adaptive time
  // step's fraction (dem/adaptive_time_step.h).
  double stability_fraction = 0;
  std::string description;
};
ContactDurations ComputeContactDurations(const std::vector<double>& radii,
                                         const Material& material);

// m = ρ (4/3) π r³ (kg).
inline double SphereMass(double radius, double density) {
  return density * 4.0 / 3.0 * 3.14159265358979323846 * radius * radius * radius;
}

}  // namespace granasym::dem
