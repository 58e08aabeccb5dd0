#include "dem/run_progress.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace granasym::dem {

std::string RunProgress::OneLine() const {
  return fmt::format(
      "stage {}/{} '{}' | step {} | {:.0f} steps/s | ETA {} | p {:.4g} kPa | e {:.4f} "
      "| psi_sigma {:.2f} deg",
      stage + 1, stages, stage_name, step, steps_per_second,
      eta_seconds < 0 ? "?" : fmt::format("{:.0f}s", eta_seconds), mean_stress_kpa, void_ratio,
      psi_sigma_deg);
}

void ProgressMeter::StartStage(int64_t step) {
  stage_clock_ = Stopwatch();
  stage_clock_start_step_ = step;
}

void ProgressMeter::Report(int64_t index, const Stage& stage, const StageClock& clock,
                           const Engine& engine, bool stage_end) {
  if (!sink_ || (!stage_end && since_progress_.Seconds() < period_s_)) return;
  since_progress_ = Stopwatch();
  const StopConditions& stop = stage.stop;
  // Fraction of the stage done, from the stop condition closest to completion.
  double fraction = 0;
  if (stop.steps) fraction = std::max(fraction, double(clock.steps(engine)) / *stop.steps);
  if (stop.time_s) fraction = std::max(fraction, (engine.time() - clock.start_time) / *stop.time_s);
  if (stop.strain_norm) fraction = std::max(fraction, clock.strain_norm / *stop.strain_norm);
  // From a contact-free start, progress in ln p counts from the first
  // positive pressure seen in the stage.
  if (eta_stage_ != index) {
    eta_stage_ = index;
    eta_p0_ = clock.start_p_kpa;
  }
  if (!(eta_p0_ > 0) && last_p_kpa_ > 0) eta_p0_ = last_p_kpa_;
  if (stop.mean_stress_kpa && last_p_kpa_ > 0 && eta_p0_ > 0) {
    const double done = std::log(last_p_kpa_ / eta_p0_);
    const double total = std::log(*stop.mean_stress_kpa / eta_p0_);
    if (total != 0) fraction = std::max(fraction, done / total);
  }
  RunProgress progress;
  progress.stage = index;
  progress.stages = stages_;
  progress.stage_name = stage.name;
  progress.step = engine.step();
  const double seconds = stage_clock_.Seconds();
  progress.steps_per_second =
      static_cast<double>(engine.step() - stage_clock_start_step_) / std::max(1e-9, seconds);
  if (stage_end) {
    progress.eta_seconds = 0;
  } else if (fraction > 1e-3 && fraction < 1) {
    progress.eta_seconds = seconds * (1 - fraction) / fraction;
  }
  progress.mean_stress_kpa = last_p_kpa_;
  progress.void_ratio = engine.void_ratio();
  progress.psi_sigma_deg = last_psi_deg_;
  sink_(progress);
}

}  // namespace granasym::dem
