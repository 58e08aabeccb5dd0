// The two files of a DEM run, written from one RunContents: the result at
// RunOptions::output_path (layout: dem/run_record_names.h) and the checkpoint
// beside it (CheckpointPath), which a restart reads back, checked against its
// scene, to continue bit-identically. Both are written atomically; a file that
// cannot be written ends the run with a FileError that says what was kept.
// Beside them: the counts of a summary, and the packing a result holds read
// back (ReadResultPacking).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "common/error.h"
#include "common/time_series.h"
#include "dem/engine.h"
#include "dem/output_columns.h"
#include "dem/packing.h"
#include "dem/run_record.h"
#include "dem/scene.h"

namespace granasym::dem {

// What a run records besides the engine and its runner's own state.
struct RunContents {
  Provenance provenance;
  // The sample of the run's lineage (a fork's is its parent's): the engine
  // orders the particles and sums the solid volume from it, and strains
  // count from its cell.
  Packing sample;
  bool generated = false;       // generated from the scene's GSD
  GenerationReport generation;  // its comparison with the GSD, when generated
  TimeSeries series{SeriesColumns()};
  std::vector<double> histogram_edges;  // of relative overlaps; empty: none
  std::vector<double> histogram_rows;   // rows x bins counts
  std::vector<StageRecord> stages;      // the finished stages
};

// The checkpoint beside the result file `output_path`.
std::string CheckpointPath(const std::string& output_path);

// The result file: scene, provenance, rows, stage records, summary, the final
// state and the sample.
void WriteResult(const std::string& path, const Scene& scene, const RunContents& contents,
                 const RunSummary& summary, const Engine& engine, int threads);

// The checkpoint: scene, provenance, sample, the engine's exact state, the
// runner's (with its controller's state and detector's samples), stage
// records and rows.
void WriteCheckpoint(const std::string& path, const Scene& scene, const RunContents& contents,
                     const Engine& engine, int threads, const RunnerRecord& runner);

// What a checkpoint holds besides RunContents.
struct CheckpointState {
  Engine::State engine;
  int threads = 0;  // the count it was written with
  RunnerRecord runner;
};

// Reads the checkpoint `path` of `scene` for a restart into `contents`, whose
// provenance holds the scene's SHA-256 (the start is taken from the
// checkpoint), and checks its runner's record against the scene and the rows
// before anything indexes with it. InputError when it is missing, of another
// scene or corrupt; `log` (may be empty) receives the warning when it was
// written with another thread count than `threads`.
CheckpointState ReadCheckpoint(const std::string& path, const Scene& scene, int threads,
                               const std::function<void(const std::string&)>& log,
                               RunContents* contents);

// The checkpoint a run keeps on disk.
struct KeptCheckpoint {
  int64_t step = -1;    // its step; -1: none written
  bool at_end = false;  // it holds the end of the last stage
};

// A file of the run that could not be written (a full disk): the run cannot
// record a failure either; throws `error` again with what was kept and how to
// continue.
[[noreturn]] void ThrowWritingFailure(const FileError& error, const KeptCheckpoint& kept,
                                      const Scene& scene, const std::string& output_path);

// The summary's counts: the engine's steps and simulated time, the recorded
// rows and stages, and the time steps of the rows: the first (the step the run
// started with, also after a restart) and the smallest and largest.
void SummarizeRun(const RunContents& contents, const Engine& engine, RunSummary* summary);

// The stages' validity flags in one line ("stage 'a': gas; ..."), "" when
// none.
std::string ValiditySummary(const std::vector<StageRecord>& stages);

// Reads a packing stored in a result file: "/final_state" (the end of the
// run) or "/sample" (the initial packing). InputError if it is missing.
Packing ReadResultPacking(const std::string& result_path, const std::string& group);

}  // namespace granasym::dem
