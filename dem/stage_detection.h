// The asymptote detection of a run's current stage: an AsymptoteDetector fed
// with samples of the engine's state, and the output row its samples start
// at. A stage that continues the previous one's path with the same criterion
// (Stage::ContinuesDetection) keeps the previous samples, their strains
// counted from its own start, and so the rows they start at.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "dem/asymptote_detector.h"
#include "dem/engine.h"
#include "dem/run_record.h"
#include "dem/stage.h"

namespace granasym::dem {

class StageDetection {
 public:
  // Stage `index` of `stages` starts at output row `first_row`, after the
  // finished stages' `records`; the previous stage ended at stage strain
  // `previous_strain`.
  void Start(const std::vector<Stage>& stages, int64_t index,
             const std::vector<StageRecord>& records, int64_t first_row, double previous_strain);
  // Stage `index`, started at `first_row`, continues with a checkpoint's
  // `samples`.
  void Restore(const std::vector<Stage>& stages, int64_t index,
               const std::vector<StageRecord>& records, int64_t first_row,
               std::vector<AsymptoteDetector::Sample> samples,
               std::optional<AsymptoteDetector::Result> held = std::nullopt);
  // A sample of the engine's state (after a force evaluation with stress) at
  // stage strain `strain`; its strains count from `reference_cell`. An
  // extension stage then keeps the window if it holds (Track).
  void AddSample(const Engine& engine, const std::array<double, 3>& reference_cell, double strain);

  const AsymptoteDetector& detector() const { return detector_; }
  // The output row of the first sample's stage.
  int64_t first_row() const { return first_row_; }

 private:
  AsymptoteDetector detector_;
  int64_t first_row_ = 0;
};

}  // namespace granasym::dem
