#include "dem/row_guards.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "dem/run_record_names.h"
#include "dem/stage_validity.h"

namespace granasym::dem {

std::optional<std::string> CheckRowGuards(const TimeSeries& series, const Stage& stage,
                                          int64_t step, bool stage_ends, StageClock* clock) {
  const ValidityLimits& limits = kValidityLimits;
  const double overlap = series.Last(record::kColumnOverlapMax);
  const double p = series.Last(record::kColumnMeanStress);
  // e <= 0 first: when both hold, it names the impossibility.
  const double e = series.Last(record::kColumnVoidRatio);
  if (!(e > 0)) {
    return fmt::format(
        "void ratio e = {:.4g} <= 0 at step {} (p = {:.4g} kPa): the cell is smaller than the "
        "solid volume; overlaps no longer describe contacts (contacts too soft for this p)",
        e, step, p);
  }
  if (overlap >= limits.overlap_failure) {
    return fmt::format(
        "relative overlap {:.3g} at step {} (p = {:.4g} kPa) reached the contact limit {:g}: "
        "spheres interpenetrate (loading too fast, time step too large, or p too high for the "
        "contact stiffness)",
        overlap, step, p, limits.overlap_failure);
  }
  const StopConditions& stop = stage.stop;
  if (!stop.mean_stress_kpa || stage_ends) return std::nullopt;
  const double target = *stop.mean_stress_kpa;
  const Direction direction = MeanStressDirection(stop, *clock);
  const double z = series.Last(record::kColumnMechanicalCoordination);
  if (!IsGas(p, z, limits)) {
    const double distance =
        direction == Direction::kRising ? std::log(target / p) : std::log(p / target);
    if (distance < clock->target_distance) {
      clock->target_distance = distance;
      clock->target_distance_strain = clock->strain_norm;
      return std::nullopt;
    }
  }
  if (std::isfinite(clock->target_distance) &&
      clock->strain_norm - clock->target_distance_strain >= limits.unreachable_strain) {
    const double closest = direction == Direction::kRising
                               ? target * std::exp(-clock->target_distance)
                               : target * std::exp(clock->target_distance);
    return fmt::format(
        "stage '{}' cannot reach its mean-stress target {:.6g} kPa ({}): p has moved away from "
        "it for {:.3g} of strain, from its closest {:.4g} kPa at stage strain {:.4g} to {:.4g} "
        "kPa at {:.4g}{}",
        stage.name, target, ToString(direction), clock->strain_norm - clock->target_distance_strain,
        closest, clock->target_distance_strain, p, clock->strain_norm,
        IsGas(p, z, limits) ? fmt::format(" (a gas: mechanical coordination {:.3g})", z) : "");
  }
  return std::nullopt;
}

std::optional<std::string> LiquefiedStop(const TimeSeries& series, const Stage& stage,
                                         StageClock* clock) {
  if (!stage.stop.liquefied) return std::nullopt;
  const double p = series.Last(record::kColumnMeanStress);
  const double z = series.Last(record::kColumnMechanicalCoordination);
  // An extension path is a dense flow with a thin network at the paper's
  // rate (SPEC §8.3-8.4): only p below the detector's floor makes it a gas.
  const bool extension = stage.asymptote.kind == PathKind::kExtension;
  const double floor_kpa =
      extension ? stage.asymptote.floor_kpa : kValidityLimits.gas_mean_stress_kpa;
  if (extension ? p >= floor_kpa : !IsGas(p, z)) {
    clock->gas_since_strain = std::numeric_limits<double>::quiet_NaN();
    return std::nullopt;
  }
  if (std::isnan(clock->gas_since_strain)) clock->gas_since_strain = clock->strain_norm;
  if (clock->strain_norm - clock->gas_since_strain <
      stage.stop.liquefied_strain.value_or(stage.asymptote.window_strain)) {
    return std::nullopt;
  }
  return fmt::format(
      "liquefied: {} on every row over {:.3g} of strain since {:.4g}; now p {:.4g} kPa, Z_m {:.3g}",
      extension ? fmt::format("p below the extension floor {:g} kPa", floor_kpa)
                : fmt::format("a gas (p below {:g} kPa or mechanical coordination below {:g})",
                              floor_kpa, kValidityLimits.gas_mechanical_coordination),
      clock->strain_norm - clock->gas_since_strain, clock->gas_since_strain, p, z);
}

}  // namespace granasym::dem
