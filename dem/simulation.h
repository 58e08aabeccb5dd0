// A DEM run of a scene: the loop that steps the engine through the scene's
// stages, measures when asked, lets each stage's controller drive the cell,
// writes the output rows and checkpoints; one HDF5 result file (layout:
// dem/run_record_names.h), bit-identical restarts from checkpoints, and runs
// that start from the saved state of another run. The loop's parts live
// beside it: the start (run_start.h), the files (run_files.h), the checks on
// each row (row_guards.h), a stage's asymptote detection and end
// (stage_detection.h, stage_end.h) and the progress (run_progress.h).
//
// The library neither prints nor handles signals: the caller receives log
// lines and progress through RunOptions and asks the run to stop through it.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "dem/packing.h"
#include "dem/run_files.h"
#include "dem/run_progress.h"
#include "dem/run_record.h"
#include "dem/scene.h"

namespace granasym::dem {

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
  // Progress, at most every progress_period_s of wall-clock time and at the
  // end of every stage.
  std::function<void(const RunProgress& progress)> progress;
  double progress_period_s = 0.25;
  // What the caller calls this run (a study case's key, study/plan.h):
  // recorded in the result's /provenance, so that a result found under
  // another case's name is known not to be that case's. Empty: none.
  std::string case_key;
  bool IsValid(std::string* why) const;
};

// Runs (or, with options.restart, continues) a scene. Throws InputError for
// bad input; numerical trouble ends the run with Termination::kFailed and the
// results so far written; a violated invariant (InvariantError) propagates.
RunSummary RunScene(const Scene& scene, const RunOptions& options);

}  // namespace granasym::dem
