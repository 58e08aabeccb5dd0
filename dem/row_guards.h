// The checks on each output row of a DEM run (SPEC §8.3): the failures that
// end the run (a void ratio e <= 0, overlaps at the contact limit, a
// mean-stress target the stage cannot reach) and the liquefied stop.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "common/time_series.h"
#include "dem/stage.h"

namespace granasym::dem {

// The failure the last row of `series` shows at engine step `step`, or
// nullopt. A stage with a mean-stress target that moves away from it: once
// the sample is not a gas, the closest approach is tracked in `clock`; stale
// for ValidityLimits::unreachable_strain of strain, the target cannot be
// reached (not checked on the row that ends the stage: `stage_ends`).
std::optional<std::string> CheckRowGuards(const TimeSeries& series, const Stage& stage,
                                          int64_t step, bool stage_ends, StageClock* clock);

// stop.liquefied: the reason when the stage's rows have been a gas over
// stop.liquefied_strain (default the detector's window), or nullopt; tracks
// the start of the latest run of gas rows in `clock`.
std::optional<std::string> LiquefiedStop(const TimeSeries& series, const Stage& stage,
                                         StageClock* clock);

}  // namespace granasym::dem
