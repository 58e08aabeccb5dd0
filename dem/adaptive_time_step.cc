#include "dem/adaptive_time_step.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "dem/contact_laws.h"
#include "dem/engine.h"
#include "dem/material.h"

namespace granasym::dem {

bool AdaptiveTimeStep::Options::IsValid(std::string* why) const {
  if (!(fraction > 0 && fraction < 1)) return *why = "fraction must be in (0, 1)", false;
  if (check_interval < 1) return *why = "check_interval must be >= 1", false;
  if (!(max_time_step > 0)) return *why = "max_time_step must be > 0", false;
  return true;
}

AdaptiveTimeStep::AdaptiveTimeStep(const Options& options, const Material& material,
                                   const std::vector<double>& radii)
    : options_(options),
      impact_duration_(ComputeContactDurations(radii, material).smallest_reduced_mass),
      overlap_dependent_(VisitContactLaw(
          material, [](auto law) { return decltype(law)::type::kOverlapDependentStiffness; })) {
  std::string why;
  GRANASYM_CHECK(options.IsValid(&why)) << why;
  GRANASYM_CHECK(impact_duration_ > 0 && std::isfinite(impact_duration_))
      << "impact duration " << impact_duration_;
}

double AdaptiveTimeStep::UpperBound() const {
  return std::min(options_.fraction * impact_duration_, options_.max_time_step);
}

double AdaptiveTimeStep::FromDuration(double smallest_duration) const {
  return std::min(options_.fraction * std::min(impact_duration_, smallest_duration),
                  options_.max_time_step);
}

double AdaptiveTimeStep::Evaluate(const Engine& engine) const {
  if (!overlap_dependent_) return UpperBound();
  return FromDuration(engine.SmallestContactDuration());
}

std::string AdaptiveTimeStep::Describe() const {
  return fmt::format(
      "adaptive: {:g} of the shortest contact duration (touching pairs at their tangent "
      "stiffness, at most the impact duration {:.4g} s of the two smallest spheres), "
      "re-evaluated every {} steps and at each stage start{}",
      options_.fraction, impact_duration_, options_.check_interval,
      std::isfinite(options_.max_time_step)
          ? fmt::format(", at most {:.4g} s", options_.max_time_step)
          : "");
}

}  // namespace granasym::dem
