#include "dem/simulation.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>

#include "common/error.h"
#include "common/provenance.h"
#include "common/state_measures.h"
#include "common/stopwatch.h"
#include "dem/adaptive_time_step.h"
#include "dem/contact_statistics.h"
#include "dem/engine.h"
#include "dem/output_columns.h"
#include "dem/row_guards.h"
#include "dem/run_files.h"
#include "dem/run_record_names.h"
#include "dem/run_start.h"
#include "dem/stage_detection.h"
#include "dem/stage_end.h"

namespace granasym::dem {
namespace {

class Simulation {
 public:
  Simulation(const Scene& scene, const RunOptions& options)
      : scene_(scene),
        options_(options),
        progress_(options.progress, options.progress_period_s,
                  static_cast<int64_t>(scene.stages.size())) {}

  RunSummary Run();

 private:
  // How the loop ended.
  struct Outcome {
    Termination termination;
    std::string message;
  };
  // What the step about to be taken must do besides advancing.
  struct StepPlan {
    int64_t stage_steps;
    bool strain_stop;  // a strain or duration stop is reached
    bool output_due, sample_due, need_stress;
    bool retime;  // the adaptive Δt is evaluated
  };
  void Start();
  void LoadCheckpoint();
  void MakeEngine(const Engine::State* state);
  Outcome Loop(const RunSummary& summary, double& loop_seconds);
  StepPlan PlanStep() const;
  // A step that measures, controls, stops, writes or re-times (and advances
  // unless its stage ends there): the failure that ends the run, or nullopt.
  std::optional<std::string> MeasuredStep(const StepPlan& plan);
  // Counts the strain of the step just taken (of length dt) on the stage's clocks.
  void CountStep(double dt);
  void StartStage();
  void AddRow();
  // Ends the current stage with its record; `failed`: the run fails in it.
  void FinishStage(const std::string& reason, bool failed = false);
  void WriteCheckpoint();
  // The results so far under the final name, beside a periodic checkpoint.
  void WritePartialResults(const RunSummary& summary);
  RunSummary Finish(RunSummary& summary, Termination termination, const std::string& message,
                    double loop_seconds, int64_t first_step, const Stopwatch& wall);
  [[noreturn]] void FailWriting(const FileError& error) const {
    ThrowWritingFailure(error, checkpoint_, scene_, options_.output_path);
  }
  void Log(const std::string& line) const {
    if (options_.log) options_.log(line);
  }
  const Stage& stage() const { return scene_.stages[runner_.stage]; }
  bool done() const { return runner_.stage >= static_cast<int64_t>(scene_.stages.size()); }

  const Scene& scene_;
  RunOptions options_;
  int threads_ = 1;
  RunContents contents_;  // provenance, sample, rows, stage records
  RunnerRecord runner_;   // stage index, clock, output counters
  std::optional<Engine> engine_;
  // The adaptive time step (scenes without a fixed numerics.time_step_s).
  std::optional<AdaptiveTimeStep> time_step_rule_;
  StageContext context_;  // the sample's diameters and the solid density
  std::unique_ptr<StageController> controller_;
  StageDetection detection_;
  KeptCheckpoint checkpoint_;  // the checkpoint on disk
  ProgressMeter progress_;
};

void Simulation::MakeEngine(const Engine::State* state) {
  const Packing& sample = contents_.sample;
  Engine::Options engine_options;
  // The fixed step, or the adaptive rule's largest: the feasibility check's
  // bound of the fewest steps holds for the whole run.
  engine_options.time_step = scene_.TimeStep(sample);
  scene_.CheckFeasible(engine_options.time_step);
  if (scene_.adaptive()) {
    time_step_rule_.emplace(scene_.adaptive_time_step, scene_.material, sample.radii);
  }
  engine_options.skin_fraction = scene_.skin_fraction;
  engine_options.threads = threads_;
  engine_.emplace(sample, scene_.material, engine_options);
  context_ = StageContext::Of(sample, scene_.material.density);
  if (state) {
    if (state->position.size() != sample.size()) {
      throw InputError(fmt::format("{}: the saved state holds {} particles, its sample {}",
                                   scene_.origin, state->position.size(), sample.size()));
    }
    // The state carries the Δt it was saved with: a restart continues with
    // it; a fixed-step scene (a fork of a run with another step) takes its
    // own; an adaptive scene re-evaluates at its first step (a stage start).
    engine_->Restore(*state);
    if (!scene_.adaptive()) engine_->SetTimeStep(engine_options.time_step);
  }
}

// A restart from the checkpoint, a fork from a parent run, or a new sample.
void Simulation::Start() {
  if (options_.restart) {
    LoadCheckpoint();
  } else if (scene_.parent) {
    const Engine::State state = StartFromParent(scene_, &contents_);
    MakeEngine(&state);
  } else {
    StartFromSample(scene_, &contents_);
    MakeEngine(nullptr);
    if (contents_.generated) Log(contents_.generation.Table());
  }
}

void Simulation::LoadCheckpoint() {
  const std::string path = CheckpointPath(options_.output_path);
  CheckpointState saved = ReadCheckpoint(path, scene_, threads_, options_.log, &contents_);
  runner_ = std::move(saved.runner);
  MakeEngine(&saved.engine);
  checkpoint_ = {saved.engine.step, done()};
  if (done()) return;
  detection_.Restore(scene_.stages, runner_.stage, contents_.stages, runner_.clock.first_row,
                     runner_.detector_samples, runner_.detector_held);
  if (!runner_.stage_started) return;
  controller_ = stage().spec->MakeController(context_);
  try {
    controller_->RestoreState(runner_.controller_state);
  } catch (const std::out_of_range&) {
    throw InputError(
        fmt::format("{}: dataset {}/controller_state holds {} values, too few for stage '{}' (the "
                    "file is corrupt, or not written by granasym)",
                    path, record::kRunner, runner_.controller_state.size(), stage().name));
  }
}

void Simulation::StartStage() {
  runner_.stage_started = true;
  StageClock& clock = runner_.clock;
  const double previous_strain = clock.strain_norm;
  clock = StageClock{};
  clock.start_step = engine_->step();
  clock.start_time = engine_->time();
  clock.start_cell = engine_->cell();
  clock.first_row = static_cast<int64_t>(contents_.series.rows());
  detection_.Start(scene_.stages, runner_.stage, contents_.stages, clock.first_row,
                   previous_strain);
  controller_ = stage().spec->MakeController(context_);
  engine_->SetVelocityGradient(controller_->Start());
}

void Simulation::AddRow() {
  const RowMeasures row(*engine_, runner_.stage, contents_.sample.cell, context_.min_diameter,
                        context_.max_diameter,
                        contents_.histogram_edges.empty() ? nullptr : &contents_.histogram_edges);
  contents_.series.AddRow(RowValues(row));
  for (int64_t count : row.contacts.histogram) {
    contents_.histogram_rows.push_back(static_cast<double>(count));
  }
  runner_.strain_since_output = 0;
  runner_.steps_since_output = 0;
  progress_.AddRow(row.stress.mean() / kKiloPascal, row.stress.psi() / kDegree);
}

void Simulation::FinishStage(const std::string& reason, bool failed) {
  StageRecord record = RecordStage(stage(), contents_.series, runner_.clock.first_row,
                                   detection_.detector(), detection_.first_row(), reason, failed);
  const bool last = runner_.stage + 1 == static_cast<int64_t>(scene_.stages.size());
  if (!failed)
    progress_.Report(runner_.stage, stage(), runner_.clock, *engine_, /*stage_end=*/true);
  if (scene_.output.stage_states && !last && !failed) record.end_state = engine_->Save();
  for (const std::string& line :
       StageEndLines(record, runner_.stage, runner_.clock.steps(*engine_))) {
    Log(line);
  }
  contents_.stages.push_back(std::move(record));
  ++runner_.stage;
  runner_.stage_started = false;
  controller_.reset();
}

void Simulation::WriteCheckpoint() {
  RunnerRecord runner = runner_;
  if (controller_) runner.controller_state = controller_->SaveState();
  runner.detector_samples = detection_.detector().samples();
  runner.detector_held = detection_.detector().last_held();
  dem::WriteCheckpoint(CheckpointPath(options_.output_path), scene_, contents_, *engine_, threads_,
                       runner);
  checkpoint_ = {engine_->step(), done()};
}

void Simulation::WritePartialResults(const RunSummary& summary) {
  RunSummary partial = summary;
  partial.termination = Termination::kInterrupted;
  partial.message = "run in progress (partial results at the last checkpoint)";
  SummarizeRun(contents_, *engine_, &partial);
  WriteResult(options_.output_path, scene_, contents_, partial, *engine_, threads_);
}

RunSummary Simulation::Finish(RunSummary& summary, Termination termination,
                              const std::string& message, double loop_seconds, int64_t first_step,
                              const Stopwatch& wall) {
  summary.termination = termination;
  summary.message = message;
  summary.loop_seconds = loop_seconds;
  summary.wall_seconds = wall.Seconds();
  summary.particle_steps_per_second =
      loop_seconds > 0 ? double(engine_->step() - first_step) * engine_->size() / loop_seconds : 0;
  summary.neighbor_builds = engine_->neighbors().builds();
  SummarizeRun(contents_, *engine_, &summary);
  try {
    if (termination != Termination::kCompleted) WriteCheckpoint();
  } catch (const FileError& error) {
    FailWriting(error);
  }
  // The stage the run failed in keeps a record of what it reached (in the
  // result file; the checkpoint holds the state before it).
  if (termination == Termination::kFailed && !done() && runner_.stage_started) {
    FinishStage(message, /*failed=*/true);
  }
  summary.validity = ValiditySummary(contents_.stages);
  if (!summary.validity.empty()) Log("validity: " + summary.validity);
  try {
    WriteResult(options_.output_path, scene_, contents_, summary, *engine_, threads_);
  } catch (const FileError& error) {
    // A completed run keeps its end in a checkpoint when there is space for
    // one (a restart then only writes the results); else the last one stays.
    if (termination == Termination::kCompleted) {
      try {
        WriteCheckpoint();
      } catch (const FileError&) {
      }
    }
    FailWriting(error);
  }
  if (termination == Termination::kCompleted && !options_.keep_checkpoint) {
    std::filesystem::remove(CheckpointPath(options_.output_path));
  }
  return summary;
}

RunSummary Simulation::Run() {
  Stopwatch wall;
  threads_ = options_.threads > 0 ? options_.threads : scene_.threads;
  if (threads_ > HardwareThreads()) {
    Log(fmt::format("warning: {} threads requested on {} hardware threads: using {}", threads_,
                    HardwareThreads(), HardwareThreads()));
    threads_ = HardwareThreads();
  }
  contents_.provenance = RunProvenance(scene_, threads_);
  contents_.provenance.case_key = options_.case_key;
  Start();
  const OutputOptions& output = scene_.output;
  if (output.overlap_histogram) {
    contents_.histogram_edges =
        LogarithmicEdges(output.histogram_min, output.histogram_max, output.histogram_bins);
  }
  const std::string time_step_rule = time_step_rule_ ? time_step_rule_->Describe() : "fixed";
  for (const std::string& line :
       StartLines(scene_, contents_.sample, threads_, engine_->time_step(), time_step_rule)) {
    Log(line);
  }
  RunSummary summary;
  summary.particles = static_cast<int64_t>(engine_->size());
  summary.threads = threads_;
  summary.time_step = engine_->time_step();
  summary.time_step_rule = time_step_rule;
  summary.stiffness_scaling = scene_.material.stiffness_scaling;
  const int64_t first_step = engine_->step();
  double loop_seconds = 0;
  Termination termination;
  std::string message;
  try {
    const Outcome outcome = Loop(summary, loop_seconds);
    termination = outcome.termination;
    message = outcome.message;
  } catch (const FileError& error) {
    FailWriting(error);  // a periodic checkpoint or partial result could not be written
  } catch (const RuntimeError& error) {
    // Keep what was computed: results and a checkpoint of the last state.
    termination = Termination::kFailed;
    message = error.what();
  }
  return Finish(summary, termination, message, loop_seconds, first_step, wall);
}

Simulation::StepPlan Simulation::PlanStep() const {
  const Stage& current = stage();
  const StageClock& clock = runner_.clock;
  const OutputOptions& output = scene_.output;
  StepPlan plan;
  plan.stage_steps = clock.steps(*engine_);
  plan.strain_stop = StrainOrDurationStopReached(current.stop, clock, *engine_);
  plan.output_due =
      contents_.series.rows() == 0 || plan.stage_steps == 0 ||
      runner_.strain_since_output >= output.interval_strain * (1 - 1e-9) ||
      (output.interval_steps > 0 && runner_.steps_since_output >= output.interval_steps);
  plan.sample_due = current.detect_asymptote && clock.strain_norm >= clock.next_sample_strain;
  plan.need_stress = plan.output_due || plan.sample_due || plan.strain_stop ||
                     controller_->NeedsStress(plan.stage_steps) ||
                     current.stop.mean_stress_kpa.has_value() || std::isnan(clock.start_p_kpa);
  plan.retime = time_step_rule_ && time_step_rule_->Due(plan.stage_steps);
  return plan;
}

void Simulation::CountStep(double dt) {
  const auto& g = engine_->velocity_gradient();
  const double increment = dt * std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  runner_.clock.strain_norm += increment;
  runner_.strain_since_output += increment;
  ++runner_.steps_since_output;
}

// One iteration per step: measure what is due, let the controller act on
// it, check the stops, write the row, then advance (or end the stage there).
Simulation::Outcome Simulation::Loop(const RunSummary& summary, double& loop_seconds) {
  Stopwatch since_checkpoint;
  while (!done()) {
    Stopwatch step_clock;
    if (!runner_.stage_started) {
      StartStage();
      progress_.StartStage(engine_->step());
    }
    const StepPlan plan = PlanStep();
    if (!plan.need_stress && !plan.retime) {
      // Nothing is measured, controlled, stopped, written or re-timed at this
      // step: forces, kick and drift in one pass (Engine::Step, bit-identical
      // to ComputeForces + Integrate).
      const double dt = engine_->time_step();
      engine_->Step({});
      CountStep(dt);
    } else if (const std::optional<std::string> failure = MeasuredStep(plan)) {
      loop_seconds += step_clock.Seconds();
      return Outcome{Termination::kFailed, *failure};
    }
    loop_seconds += step_clock.Seconds();

    if (!done()) progress_.Report(runner_.stage, stage(), runner_.clock, *engine_);
    if (options_.stop_requested && options_.stop_requested(engine_->step())) {
      return Outcome{
          Termination::kInterrupted,
          fmt::format("interrupted at step {}; continue with --restart", engine_->step())};
    }
    if ((engine_->step() & 255) == 0 &&
        since_checkpoint.Seconds() >= scene_.output.checkpoint_interval_s) {
      WriteCheckpoint();
      WritePartialResults(summary);
      since_checkpoint = Stopwatch();
    }
  }
  return Outcome{Termination::kCompleted, "all stages completed"};
}

std::optional<std::string> Simulation::MeasuredStep(const StepPlan& plan) {
  const Stage& current = stage();
  StageClock& clock = runner_.clock;
  engine_->ComputeForces({plan.need_stress, controller_->NeedsStiffness()});
  // The adaptive Δt from the contacts just evaluated, before anything uses
  // this step's Δt: the controller's rate, the step itself, its strain.
  if (plan.retime) {
    const double next = time_step_rule_->Evaluate(*engine_);
    if (next != engine_->time_step()) engine_->SetTimeStep(next);
  }
  const double dt = engine_->time_step();
  double p = std::numeric_limits<double>::quiet_NaN();
  if (plan.need_stress) {
    p = MeanStressKpa(engine_->sums());
    if (!std::isfinite(p)) {
      return fmt::format(
          "non-finite stress at step {}: the motion became unstable (time step {:.3g} s too "
          "large for the contact stiffness?)",
          engine_->step(), dt);
    }
    if (std::isnan(clock.start_p_kpa)) clock.start_p_kpa = p;
    if (const auto gradient = controller_->Control(engine_->sums(), dt)) {
      engine_->SetVelocityGradient(*gradient);
    }
  }
  if (plan.sample_due) {
    detection_.AddSample(*engine_, contents_.sample.cell, clock.strain_norm);
    clock.next_sample_strain += current.asymptote.sample_strain;
  }
  std::optional<std::string> reason;
  if (plan.need_stress) reason = MeanStressStop(current.stop, clock, p);
  if (!reason && plan.sample_due && current.stop.asymptote) {
    reason = AsymptoteStop(detection_.detector().Evaluate(), current.asymptote.kind,
                           contents_.series, detection_.first_row(), clock.first_row);
  }
  if (!reason && plan.need_stress) reason = controller_->CheckStop(*engine_, plan.stage_steps);
  if (!reason && plan.strain_stop) reason = StrainOrDurationReason(current.stop, clock, *engine_);
  if (plan.output_due || reason) {
    AddRow();
    if (std::optional<std::string> failure = CheckRowGuards(
            contents_.series, current, engine_->step(), reason.has_value(), &clock)) {
      return failure;
    }
    if (!reason) reason = LiquefiedStop(contents_.series, current, &clock);
  }
  if (reason) {
    // The stage ends at the state that met its condition (its last row);
    // the next stage starts from the same state: the engine re-evaluates
    // its forces there without advancing the shear history.
    FinishStage(*reason);
  } else {
    engine_->Integrate();
    CountStep(dt);
  }
  return std::nullopt;
}

}  // namespace

bool RunOptions::IsValid(std::string* why) const {
  if (output_path.empty()) return *why = "output_path is empty", false;
  if (threads < 0) return *why = "threads must be >= 0 (0: the scene's)", false;
  if (!(progress_period_s >= 0)) return *why = "progress_period_s must be >= 0", false;
  return true;
}

RunSummary RunScene(const Scene& scene, const RunOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("run options: " + why);
  if (scene.parent && std::filesystem::exists(options.output_path) &&
      std::filesystem::equivalent(scene.parent->path, options.output_path)) {
    throw InputError(scene.origin + ": --out '" + options.output_path +
                     "' is the parent state the scene starts from: no output overwrites an input");
  }
  Simulation simulation(scene, options);
  return simulation.Run();
}

}  // namespace granasym::dem
