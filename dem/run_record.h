// The records of a DEM run, each with one writer and one reader shared by the
// result file and the checkpoint (names: dem/run_record_names.h): the scene,
// the sample, the series with its histograms, the stage records with their
// asymptotes and end states, the summary, the exact engine state (particles,
// cell, neighbour list with its pair order and shear history), the runner's
// own state and the provenance.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "common/enum_names.h"
#include "common/time_series.h"
#include "dem/asymptote_detector.h"
#include "dem/engine.h"
#include "dem/material.h"
#include "dem/packing.h"
#include "dem/stage.h"
#include "dem/stage_validity.h"

namespace granasym {
class Hdf5File;
}

namespace granasym::dem {

enum class Termination { kNotRun, kCompleted, kInterrupted, kFailed };
}  // namespace granasym::dem

template <>
struct granasym::EnumNames<granasym::dem::Termination> {
  static constexpr EnumEntry<dem::Termination> kEntries[] = {
      {dem::Termination::kNotRun, "not_run", "the run has not started"},
      {dem::Termination::kCompleted, "completed", "all stages completed"},
      {dem::Termination::kInterrupted, "interrupted",
       "stopped on request; continue with --restart"},
      {dem::Termination::kFailed, "failed", "a numerical failure; results up to it are kept"},
  };
};

namespace granasym::dem {

struct RunSummary {
  Termination termination = Termination::kNotRun;
  std::string message = "not run";
  std::string validity;  // the stages' validity flags ("stage 'a': gas; ..."), "" when none
  int64_t steps = 0;     // steps taken in total (including before a restart or fork)
  int64_t particles = 0;
  double simulated_time = 0;  // (s)
  double wall_seconds = 0;    // this invocation
  double loop_seconds = 0;    // time-stepping only, this invocation
  double particle_steps_per_second = 0;
  int64_t neighbor_builds = 0;
  int64_t rows = 0;
  int64_t stages_completed = 0;
  int threads = 1;
  // Δt of the run's first row (s), and the smallest and largest of its rows
  // (they differ under the adaptive rule).
  double time_step = 0;
  double min_time_step = 0, max_time_step = 0;
  std::string time_step_rule = "fixed";  // "fixed", or AdaptiveTimeStep::Describe()
  double stiffness_scaling = 1;          // Material::stiffness_scaling
  std::string OneLine() const;
};

// The asymptote of a stage whose detector ran, in the units of the file:
// its kind, status, criterion, the window used, the state over it and the
// criterion's measures. The state is the mean over the window when a full
// window was available (status detected or drifting, and gas or invalid
// after one), else the stage end (its last row).
struct AsymptoteRecord {
  PathKind path_kind = PathKind::kIsochoric;
  AsymptoteStatus status = AsymptoteStatus::kNotReached;
  bool detected = false;         // status == kDetected
  AsymptoteCriterion criterion;  // the kind's window and tolerances
  double window_strain = 0;      // the window used: its strain span
  double window_lnp = 0;         // and its |Δ ln p|
  // The state at the asymptote.
  double mean_stress_kpa = 0;
  double void_ratio = 0;
  double psi_sigma_deg = 0;
  double psi_epsilon_deg = 0;  // from the strain increments over the window
  double q_over_p = 0;
  double coordination = 0;
  double mechanical_coordination = 0;
  double inertial_number_dmin = 0;
  double inertial_number_dmax = 0;
  double max_relative_overlap = 0;  // the largest over the window's rows
  // The criterion's measures over the window (AsymptoteDetector::Result).
  double psi_change_deg = 0;          // fitted change of ψ_σ across the window
  double lnp_change = 0;              // fitted change of ln p across the window
  double lnp_half_difference = 0;     // |Δln p (2nd half) − Δln p (1st half)|
  double slope_change = 0;            // relative change of d ln(1+e)/d ln p between halves
  double psi_epsilon_change_deg = 0;  // |ψ_ε (2nd half) − ψ_ε (1st half)|
  double lnv_change = 0;              // fitted change of ln(1+e) across the window
  double dlnp_dstrain = 0;            // d ln p / dε over the window
  double dln1pe_dlnp = 0;             // d ln(1+e) / d ln p over the window (−λ* on a line)
  // The range of p over the window's samples (NaN without a window, and in
  // records written before it was kept).
  double p_min_kpa = std::numeric_limits<double>::quiet_NaN();
  double p_max_kpa = std::numeric_limits<double>::quiet_NaN();
  // Extension: the state is the last window that held, before the stage's
  // end (the path went on: below the floor, or drifting).
  bool before_end = false;

  // The window of a detector's result, its state (means over the window,
  // when there is one: window_strain > 0) and the criterion's measures; the
  // kind, status, criterion and the rows' measures are the caller's.
  void SetWindow(const AsymptoteDetector::Result& result);
};

// One finished stage.
struct StageRecord {
  std::string name, type;
  int64_t first_row = 0, last_row = 0;
  std::string stop_reason;
  bool failed = false;  // the run failed in this stage (the record of what it reached)
  StageValidity validity;
  std::optional<AsymptoteRecord> asymptote;  // when the detector ran
  std::string asymptote_criterion;           // its one-line description
  std::optional<Engine::State> end_state;    // the state the next stage starts from, when kept
};

// The runner's state besides the engine (checkpoint only).
struct RunnerRecord {
  int64_t stage = 0;  // index of the current stage
  bool stage_started = false;
  StageClock clock;
  double strain_since_output = 0;
  int64_t steps_since_output = 0;
  std::vector<double> controller_state;
  std::vector<AsymptoteDetector::Sample> detector_samples;
  std::optional<AsymptoteDetector::Result> detector_held;  // the last extension window that held
};

struct Provenance {
  std::string program_version;
  std::string scene_canonical;  // the parsed, defaulted scene
  std::string scene_sha256;     // of scene_canonical
  std::string start_kind;       // "generated", "packing" or "state"
  std::string start_sha256;     // of the starting packing or parent state
  std::string parent_file, parent_stage, parent_scene_sha256;  // forks only
  int64_t threads = 0;
  std::string cpu_model;
  std::string case_key;  // RunOptions::case_key ("" when none was given)
};

// The sample and, when generated, its GSD comparison (report may be null).
void WriteSample(Hdf5File& file, const Packing& packing, const GenerationReport* report);
// Reads /sample; returns true and fills `report` (may be null) when it was generated.
bool ReadSample(const Hdf5File& file, Packing* packing, GenerationReport* report);

void WritePacking(Hdf5File& file, const std::string& group, const Packing& packing);
Packing ReadPacking(const Hdf5File& file, const std::string& group);

void WriteEngineState(Hdf5File& file, const std::string& group, const Engine::State& state,
                      int threads);
Engine::State ReadEngineState(const Hdf5File& file, const std::string& group,
                              int* threads = nullptr);
// The current packing, velocities and spins in input order, and the exact
// engine state below group/engine.
void WriteFinalState(Hdf5File& file, const Engine& engine, int threads);

// Histograms of relative overlaps: bin edges and rows × bins counts.
void WriteHistograms(Hdf5File& file, const std::vector<double>& edges,
                     const std::vector<double>& rows);
std::vector<double> ReadHistogramRows(const Hdf5File& file);

// `stage` (may be null) adds the stage type's own keys; `threads` is stored
// with the end state (bit-identical continuations need the same count).
void WriteStageRecord(Hdf5File& file, const std::string& group, const StageRecord& record,
                      const StageSpec* stage, int threads);
StageRecord ReadStageRecord(const Hdf5File& file, const std::string& group);
// All records below /stages, in order.
void WriteStageRecords(Hdf5File& file, const std::vector<StageRecord>& records,
                       const std::vector<Stage>& stages, int threads);
std::vector<StageRecord> ReadStageRecords(const Hdf5File& file);
// The engine step of the end state kept for the stage named `stage` (the
// state a fork from it starts at), read from its attributes alone; nullopt
// when no stage of that name kept one.
std::optional<int64_t> StageEndStep(const Hdf5File& file, const std::string& stage);
std::string StageGroup(size_t index);  // "/stages/007"

void WriteSummary(Hdf5File& file, const RunSummary& summary, const ContactDurations& durations);
RunSummary ReadSummary(const Hdf5File& file);

void WriteRunner(Hdf5File& file, const RunnerRecord& runner);
RunnerRecord ReadRunner(const Hdf5File& file);

void WriteProvenance(Hdf5File& file, const Provenance& provenance);
Provenance ReadProvenance(const Hdf5File& file);
// The material the run used, from its provenance's canonical scene.
Material ReadMaterial(const Hdf5File& file);
// The rate of strain-path stage `index` as a label: "I* = 0.001" (inertial
// rule) or "‖D‖ = 167 1/s"; empty for a stage without a stretching rate.
std::string StageRateLabel(const Hdf5File& file, size_t index);

// A result file in one line per item (`granasym export --info`): the program
// version, the scene and its origin, the start, the termination and its
// message, whether it is final, the checkpoint beside it, the counters, the
// validity flags and each stage with its rows, stop reason and asymptote.
std::string DescribeResult(const Hdf5File& file);
// "" for the result of a completed run; else one sentence: the file is not a
// final result (an interrupted run, or one still running, writes its partial
// results under the final name), with the termination, the message and how to
// continue it.
std::string PartialResultNote(const Hdf5File& file);

}  // namespace granasym::dem
