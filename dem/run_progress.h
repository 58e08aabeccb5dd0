// Where a DEM run stands, for its caller's progress display: the stage, the
// speed, the time the stage has left (from the stop condition closest to
// completion) and the state of the last row.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>

#include "common/stopwatch.h"
#include "dem/engine.h"
#include "dem/stage.h"

namespace granasym::dem {

// Where a run stands, handed to RunOptions::progress.
struct RunProgress {
  int64_t stage = 0;  // 0-based
  int64_t stages = 0;
  std::string stage_name;
  int64_t step = 0;
  double steps_per_second = 0;                                    // in this stage, this invocation
  double eta_seconds = -1;                                        // of the stage; < 0 when unknown
  double mean_stress_kpa = 0, void_ratio = 0, psi_sigma_deg = 0;  // of the last row
  std::string OneLine() const;
};

// Measures a run's progress and hands it to `sink` at most every `period_s`
// of wall-clock time, and once at the end of every stage (so that a caller
// hears of a stage shorter than the period). Not part of the run's state.
class ProgressMeter {
 public:
  ProgressMeter(std::function<void(const RunProgress&)> sink, double period_s, int64_t stages)
      : sink_(std::move(sink)), period_s_(period_s), stages_(stages) {}

  // The stage clock starts (steps per second count from `step`).
  void StartStage(int64_t step);
  // The state of the latest row.
  void AddRow(double mean_stress_kpa, double psi_sigma_deg) {
    last_p_kpa_ = mean_stress_kpa;
    last_psi_deg_ = psi_sigma_deg;
  }
  // Hands the progress of stage `index` to the sink when the period since
  // the last has passed, or always when `stage_end` (the stage has just
  // ended: its ETA is 0).
  void Report(int64_t index, const Stage& stage, const StageClock& clock, const Engine& engine,
              bool stage_end = false);

 private:
  std::function<void(const RunProgress&)> sink_;
  double period_s_;
  int64_t stages_;
  double last_p_kpa_ = 0, last_psi_deg_ = 0;
  Stopwatch stage_clock_, since_progress_;
  int64_t stage_clock_start_step_ = 0;
  // The stage whose ETA is measured and the mean stress (kPa) its progress
  // in ln p counts from.
  int64_t eta_stage_ = -1;
  double eta_p0_ = 0;
};

}  // namespace granasym::dem
