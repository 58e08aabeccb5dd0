// A DEM run of a scene: the loop that steps the engine through the scene's
// stages, measures when asked, lets each stage's controller drive the cell,
// writes the output rows and checkpoints; one HDF5 result file (layout:
// dem/run_record_names.h), bit-identical restarts from checkpoints, and runs
// that start from the saved state of another run.
//
// The library neither prints nor handles signals: the caller receives log
// lines and progress through RunOptions and asks the run to stop through it.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "dem/packing.h"
#include "dem/run_record.h"
#include "dem/scene.h"

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

struct RunOptions {
  std::string output_path = "run.h5";  // result file; checkpoint at output_path + ".ckpt"
  int threads = 0;                     // 0: the scene's numerics.threads
  bool restart = false;                // continue from the checkpoint
  bool keep_checkpoint = false;        // keep the checkpoint after completion
  // Polled once per step with the step index; true interrupts the run: it
  // writes a checkpoint and the results so far (Termination::kInterrupted).
  std::function<bool(int64_t step)> stop_requested;
  // Whole lines of the run's report (sample, time step, stage ends, warnings).
  std::function<void(const std::string& line)> log;
  // Progress, at most every progress_period_s of wall-clock time.
  std::function<void(const RunProgress& progress)> progress;
  double progress_period_s = 0.25;
  bool IsValid(std::string* why) const;
};

// Runs (or, with options.restart, continues) a scene. Throws InputError for
// bad input; numerical trouble ends the run with Termination::kFailed and the
// results so far written; a violated invariant (InvariantError) propagates.
RunSummary RunScene(const Scene& scene, const RunOptions& options);

// Reads a packing stored in a result file: "/final_state" (the end of the
// run) or "/sample" (the initial packing). InputError if it is missing.
Packing ReadResultPacking(const std::string& result_path, const std::string& group);

}  // namespace granasym::dem
