// A DEM run of a scene: chained loading stages with their controllers and
// stop conditions, measurements at each output interval, one HDF5 result
// file, periodic and on-signal checkpoints, and bit-identical restarts.
//
// Result file layout (all stresses kPa, compression positive):
//   /scene                 the scene text as given (attribute origin)
//   /series/<column>       time series, one dataset per column with `units`
//   /series_histogram/...  relative-overlap histograms when requested
//   /stages/<k>            per stage: name, type, rows, stop reason, asymptote
//   /summary               attributes: termination, message, counters, times,
//                          time step and contact durations
//   /final_state           cell (m), positions (N×3, m), radii, velocities,
//                          spins, in the order of the input packing
//   /sample                the initial packing (and the GSD report if generated)
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "dem/scene.h"

namespace granasym::dem {

enum class Termination { kCompleted, kInterrupted, kFailed };
std::string ToString(Termination termination);

struct RunOptions {
  std::string output_path = "run.h5";  // result file; checkpoint at output_path + ".ckpt"
  int threads = 0;                     // 0: the scene's numerics.threads
  bool restart = false;                // continue from the checkpoint
  bool quiet = false;                  // no progress output
  bool keep_checkpoint = false;        // keep the checkpoint after completion
  // Testing aid: behave as if interrupted after this many steps (-1: never).
  int64_t interrupt_after_steps = -1;
  bool IsValid(std::string* why) const;
};

struct RunSummary {
  Termination termination = Termination::kCompleted;
  std::string message;
  int64_t steps = 0;            // steps taken in total (including before a restart)
  int64_t particles = 0;
  double simulated_time = 0;    // (s)
  double wall_seconds = 0;      // this invocation
  double loop_seconds = 0;      // time-stepping only, this invocation
  double particle_steps_per_second = 0;
  int64_t neighbor_builds = 0;
  int64_t rows = 0;
  int threads = 1;
  double time_step = 0;
  std::string OneLine() const;
};

// Runs (or, with options.restart, continues) a scene. Throws InputError for
// bad input; numerical trouble ends the run with Termination::kFailed and the
// results so far written.
RunSummary RunScene(const Scene& scene, const RunOptions& options);

// Reads a packing stored in a result file: "/final_state" (the end of the
// run) or "/sample" (the initial packing). InputError if it is missing.
Packing ReadResultPacking(const std::string& result_path, const std::string& group);


}  // namespace granasym::dem
