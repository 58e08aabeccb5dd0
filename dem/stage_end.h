// How a stage of a DEM run ends: the stop at a detected asymptote, and the
// record of a finished stage (its rows, validity and asymptote) with its lines
// for the run's log.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/time_series.h"
#include "dem/asymptote_detector.h"
#include "dem/run_record.h"
#include "dem/stage.h"

namespace granasym::dem {

// The stop reason when the detector's `result` is an asymptote of `kind`: a
// detection over rows (from the detector's first row `detector_first_row` to
// the last, which must be a row of the stage starting at `stage_first_row`)
// that are neither a gas nor overlapping beyond the reliable; else nullopt
// (the stage goes on: a compression path leaves a loose start behind).
std::optional<std::string> AsymptoteStop(const AsymptoteDetector::Result& result, PathKind kind,
                                         const TimeSeries& series, int64_t detector_first_row,
                                         int64_t stage_first_row);

// How an extension path went on after the last window that held above its
// floor (SPEC §8.4), for the stop reason of a state kept from before the end:
// "left the valid range p >= F kPa" where its last window `end` reaches below
// `floor_kpa` or its last row is below it (p `p_end_kpa`), else "drifted".
std::string AfterLastHeld(const AsymptoteDetector::Result& end, double p_end_kpa, double floor_kpa);

// The record of `stage`, whose rows start at `first_row`, ending for
// `reason` (`failed`: the run fails in it): its validity and, with detection,
// its asymptote over the detector's window (its samples start at row
// `detector_first_row`) or at its last row. The end state is left to the
// caller.
StageRecord RecordStage(const Stage& stage, const TimeSeries& series, int64_t first_row,
                        const AsymptoteDetector& detector, int64_t detector_first_row,
                        const std::string& reason, bool failed);

// The log lines of stage `index` (0-based) ended after `steps` steps.
std::vector<std::string> StageEndLines(const StageRecord& record, int64_t index, int64_t steps);

}  // namespace granasym::dem
