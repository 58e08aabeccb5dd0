#include "dem/material.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/canonical_text.h"
#include "common/config.h"
#include "common/error.h"
#include "common/state_measures.h"
#include "dem/contact_laws.h"

namespace granasym::dem {
namespace {

template <class Law>
ContactDurations Durations(const std::vector<double>& radii, const Material& material) {
  GRANASYM_CHECK(!radii.empty());
  const typename Law::Params params = Law::Params::FromMaterial(material);
  const auto [smallest, largest] = std::minmax_element(radii.begin(), radii.end());
  auto duration = [&](double r, bool reduced) {
    const double m = SphereMass(r, material.density);
    return Law::ImpactDuration(params, r, reduced ? 0.5 * m : m);
  };
  ContactDurations d;
  d.smallest_reduced_mass = duration(*smallest, true);
  d.largest_reduced_mass = duration(*largest, true);
  d.smallest_single_mass = duration(*smallest, false);
  d.largest_single_mass = duration(*largest, false);
  // The two smallest spheres form the stiffest pair relative to their mass.
  std::vector<double> two(2);
  std::partial_sort_copy(radii.begin(), radii.end(), two.begin(), two.end());
  if (radii.size() == 1) two[1] = two[0];
  const double k_n = Law::StabilityStiffness(params, two[0], two[1]);
  const double mass0 = SphereMass(two[0], material.density);
  const double mass1 = SphereMass(two[1], material.density);
  const double inverse_mass = 1.0 / mass0 + 1.0 / mass1;
  double factor =
      material.has_friction() ? std::max(1.0, 3.5 * Law::TangentialStiffnessRatio(params)) : 1.0;
  if constexpr (Law::kRollingHistory) {
    const double reduced_radius = two[0] * two[1] / (two[0] + two[1]);
    const double k_r = RollingStiffness(params.rolling_friction, reduced_radius, k_n);
    const double inverse_inertia =
        1.0 / (0.4 * mass0 * two[0] * two[0]) + 1.0 / (0.4 * mass1 * two[1] * two[1]);
    factor = std::max(factor, k_r * inverse_inertia / (k_n * inverse_mass));
  }
  d.critical_time_step = 2.0 / std::sqrt(k_n * inverse_mass * factor);
  d.stability_fraction = 2.0 / (kPi * std::sqrt(factor));
  d.description = Law::DurationDescription() +
                  "; durations of two equal spheres (smallest, largest) with m_12 = m/2 "
                  "(reduced) and m_12 = m (single); stability limit of the two smallest spheres";
  return d;
}

std::string Number(double value) { return fmt::format("{}", value); }

}  // namespace

bool Material::IsValid(std::string* why) const {
  if (!(youngs_modulus > 0)) return *why = "youngs_modulus must be > 0", false;
  switch (contact_law) {
    case ContactLaw::kLinear:
      if (!(stiffness_ratio >= 0)) return *why = "stiffness_ratio must be >= 0", false;
      break;
    case ContactLaw::kHertzMindlin:
      if (!(poissons_ratio > -1 && poissons_ratio < 0.5)) {
        return *why = "poissons_ratio must be in (-1, 0.5)", false;
      }
      break;
  }
  if (!(friction_angle >= 0 && friction_angle < kPi / 2)) {
    return *why = "friction_angle must be in [0, pi/2) rad", false;
  }
  if (!(rolling_friction >= 0)) return *why = "rolling_friction must be >= 0", false;
  if (has_rolling_resistance() && !has_friction()) {
    return *why =
               "rolling_friction > 0 needs friction (friction_angle > 0 and, for the linear "
               "law, stiffness_ratio > 0): without tangential forces no sphere spins",
           false;
  }
  if (!(density > 0)) return *why = "density must be > 0", false;
  if (!(stiffness_scaling > 0 && stiffness_scaling <= 1)) {
    return *why = "stiffness_scaling must be in (0, 1]", false;
  }
  if (!(local_damping >= 0 && local_damping < 1)) {
    return *why = "local_damping must be in [0, 1)", false;
  }
  return true;
}

bool Material::has_friction() const {
  if (!(friction_angle > 0)) return false;
  return contact_law != ContactLaw::kLinear || stiffness_ratio > 0;
}

double Material::friction_coefficient() const { return std::tan(friction_angle); }

namespace {
// From soft rubber-like grains (1 kPa) to diamond (1.2e6 MPa), with a decade
// to spare on each side: the range of a sane material, not a physical limit.
const Range kYoungsModulusMpa = Range::Closed(1e-3, 1e7);
}  // namespace

Material ParseMaterial(const ConfigTable& table) {
  Material material;
  material.contact_law = table.GetEnum("contact_law", material.contact_law);
  const bool linear = material.contact_law == ContactLaw::kLinear;
  material.youngs_modulus =
      table.GetDouble("youngs_modulus_mpa", material.youngs_modulus * 1e-6, kYoungsModulusMpa) *
      1e6;
  // Each law's own elastic constant; the other law's key is an error rather
  // than silently ignored (ν means different things in the two laws).
  const char* other_key = linear ? "poissons_ratio" : "stiffness_ratio";
  if (table.Has(other_key)) {
    const double value = table.GetDouble(other_key);
    if (linear) {
      table.Fail(other_key, "= " + Number(value) +
                                " applies to contact_law = 'hertz_mindlin' only: the linear law "
                                "takes stiffness_ratio = k_s/k_n >= 0 (or set contact_law = "
                                "'hertz_mindlin')");
    }
    table.Fail(other_key, "= " + Number(value) +
                              " applies to contact_law = 'linear' only: 'hertz_mindlin' takes "
                              "poissons_ratio in (-1, 0.5) (the material's Poisson's ratio)");
  }
  if (linear) {
    material.stiffness_ratio =
        table.GetDouble("stiffness_ratio", material.stiffness_ratio, Range::Closed(0.0, 10.0));
  } else {
    material.poissons_ratio =
        table.GetDouble("poissons_ratio", material.poissons_ratio, Range::Open(-1.0, 0.5));
  }
  material.friction_angle =
      table.GetDouble("friction_angle_rad", material.friction_angle, {0.0, kPi / 2, true, false});
  material.rolling_friction =
      table.GetDouble("rolling_friction", material.rolling_friction, Range::Closed(0.0, 10.0));
  material.density = table.GetDouble("density_kg_m3", material.density, Range::Closed(1.0, 1e5));
  material.local_damping =
      table.GetDouble("local_damping", material.local_damping, {0.0, 1.0, true, false});
  material.stiffness_scaling =
      table.GetDouble("stiffness_scaling", material.stiffness_scaling, {0.0, 1.0, false, true});
  if (material.has_rolling_resistance() && !material.has_friction()) {
    table.Fail("rolling_friction",
               "= " + Number(material.rolling_friction) +
                   " needs sliding friction: friction_angle_rad > 0" +
                   (linear ? " and stiffness_ratio > 0" : "") +
                   " (without tangential forces no sphere spins); or set rolling_friction = 0");
  }
  table.CheckNoUnknownKeys();
  std::string why;
  GRANASYM_CHECK(material.IsValid(&why)) << why;
  return material;
}

double Material::StiffnessNumber(double mean_stress) const {
  if (!(mean_stress > 0)) return std::numeric_limits<double>::infinity();
  return VisitContactLaw(*this, [&](auto law) {
    using Law = typename decltype(law)::type;
    return Law::StiffnessNumber(Law::Params::FromMaterial(*this), mean_stress);
  });
}

void Material::Canonical(CanonicalText& text, const std::string& prefix) const {
  text.Add(prefix + "contact_law", ToString(contact_law));
  text.Add(prefix + "youngs_modulus_mpa", youngs_modulus * 1e-6);
  if (contact_law == ContactLaw::kLinear) {
    text.Add(prefix + "stiffness_ratio", stiffness_ratio);
  } else {
    text.Add(prefix + "poissons_ratio", poissons_ratio);
  }
  text.Add(prefix + "friction_angle_rad", friction_angle);
  text.Add(prefix + "rolling_friction", rolling_friction);
  text.Add(prefix + "density_kg_m3", density);
  text.Add(prefix + "local_damping", local_damping);
  text.Add(prefix + "stiffness_scaling", stiffness_scaling);
}

ContactDurations ComputeContactDurations(const std::vector<double>& radii,
                                         const Material& material) {
  return VisitContactLaw(
      material, [&](auto law) { return Durations<typename decltype(law)::type>(radii, material); });
}

}  // namespace granasym::dem
