#include "dem/simulation.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>

#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/provenance.h"
#include "common/state_measures.h"
#include "common/stopwatch.h"
#include "common/time_series.h"
#include "dem/adaptive_time_step.h"
#include "dem/asymptote_detector.h"
#include "dem/contact_statistics.h"
#include "dem/engine.h"
#include "dem/output_columns.h"
#include "dem/run_record_names.h"
#include "dem/stage_validity.h"

namespace granasym::dem {
namespace {

template <typename Value>
void HashVector(Sha256& hash, const std::vector<Value>& values) {
  hash.Update(values.data(), values.size() * sizeof(Value));
}

std::string HashPacking(const Packing& packing) {
  Sha256 hash;
  hash.Update(packing.cell.data(), sizeof(packing.cell));
  HashVector(hash, packing.positions);
  HashVector(hash, packing.radii);
  return hash.HexDigest();
}

std::string HashEngineState(const Engine::State& state) {
  Sha256 hash;
  HashVector(hash, state.position);
  HashVector(hash, state.velocity);
  HashVector(hash, state.spin);
  HashVector(hash, state.id);
  hash.Update(state.cell.data(), sizeof(state.cell));
  hash.Update(state.gradient.data(), sizeof(state.gradient));
  hash.Update(&state.time, sizeof(state.time));
  hash.Update(&state.step, sizeof(state.step));
  hash.Update(&state.time_step, sizeof(state.time_step));
  HashVector(hash, state.neighbors.offsets);
  HashVector(hash, state.neighbors.neighbors);
  HashVector(hash, state.neighbors.shear);
  HashVector(hash, state.neighbors.rolling);
  return hash.HexDigest();
}

// The time steps of the rows: the first (the step the run started with,
// also after a restart) and the smallest and largest.
void SummarizeTimeSteps(const TimeSeries& series, RunSummary* summary) {
  if (series.rows() == 0) {
    summary->min_time_step = summary->max_time_step = summary->time_step;
    return;
  }
  const std::vector<double>& steps = series.Values(record::kColumnTimeStep);
  summary->time_step = steps.front();
  const auto [smallest, largest] = std::minmax_element(steps.begin(), steps.end());
  summary->min_time_step = *smallest;
  summary->max_time_step = *largest;
}

class Simulation {
 public:
  Simulation(const Scene& scene, const RunOptions& options)
      : scene_(scene), options_(options), series_(SeriesColumns()) {}

  RunSummary Run();

 private:
  void Setup();
  void Fork();
  void LoadCheckpoint();
  void MakeEngine(const Engine::State* state);
  void StartStage();
  void AddRow();
  // The guards checked on every output row: a failure message, or nullopt.
  std::optional<std::string> CheckRowGuards(bool stage_ends);
  // stop.liquefied: the reason when the stage's rows have been a gas over
  // stop.liquefied_strain (default the detector's window); tracks the start
  // of the latest run of gas rows.
  std::optional<std::string> LiquefiedStop();
  // Ends the current stage with its record; `failed`: the run fails in it.
  void FinishStage(const std::string& reason, bool failed = false);
  // How the loop ended.
  struct Outcome {
    Termination termination;
    std::string message;
  };
  Outcome Loop(const RunSummary& summary, double& loop_seconds);
  RunSummary Finish(RunSummary& summary, Termination termination, const std::string& message,
                    double loop_seconds, int64_t first_step, const Stopwatch& wall);
  void WriteResults(const RunSummary& summary) const;
  void WriteCheckpoint();
  void CheckCheckpoint(const std::string& path) const;
  // A file that could not be written (a full disk): the run cannot record a
  // failure either; rethrows with what was kept.
  [[noreturn]] void FailWriting(const FileError& error) const;
  void ReportProgress();
  void Log(const std::string& line) const {
    if (options_.log) options_.log(line);
  }
  const Stage& stage() const { return scene_.stages[runner_.stage]; }
  bool done() const { return runner_.stage >= static_cast<int64_t>(scene_.stages.size()); }

  const Scene& scene_;
  RunOptions options_;
  int threads_ = 1;
  Packing initial_;  // the sample of the lineage: engine order, solid volume, strain origin
  GenerationReport generation_;
  bool generated_ = false;
  Provenance provenance_;
  std::optional<Engine> engine_;
  // The adaptive time step (scenes without a fixed numerics.time_step_s).
  std::optional<AdaptiveTimeStep> time_step_rule_;
  double min_diameter_ = 0, max_diameter_ = 0;
  TimeSeries series_;
  std::vector<double> histogram_edges_;
  std::vector<double> histogram_rows_;  // rows x bins
  RunnerRecord runner_;                 // stage index, clock, output counters
  std::unique_ptr<StageController> controller_;
  AsymptoteDetector detector_;
  // The first output row of the detector's samples: the stage's, or that of
  // the first stage of a chain that continues one path (Stage::ContinuesDetection).
  int64_t detector_first_row_ = 0;
  int64_t DetectorFirstRow() const;
  // The sample's diameters and the solid density, for the stage controllers.
  StageContext Context() const;
  std::vector<StageRecord> records_;
  int64_t checkpoint_step_ = -1;    // the step of the checkpoint on disk; -1: none
  bool checkpoint_at_end_ = false;  // it holds the end of the last stage
  // Progress reporting only; not part of the state.
  double last_p_kpa_ = 0, last_psi_deg_ = 0;
  Stopwatch stage_clock_, since_progress_;
  int64_t stage_clock_start_step_ = 0;
  int64_t eta_stage_ = -1;
  double eta_p0_ = 0;
};

StageContext Simulation::Context() const {
  StageContext context;
  context.density = scene_.material.density;
  if (initial_.radii.empty()) return context;
  std::vector<std::pair<double, double>> by_size;  // (radius, mass ∝ r³)
  double total = 0;
  for (double r : initial_.radii) {
    by_size.push_back({r, r * r * r});
    total += r * r * r;
  }
  std::sort(by_size.begin(), by_size.end());
  context.min_diameter = 2 * by_size.front().first;
  context.max_diameter = 2 * by_size.back().first;
  double passing = 0;
  for (const auto& [r, mass] : by_size) {
    passing += mass;
    if (passing >= 0.5 * total) {
      context.median_diameter = 2 * r;
      break;
    }
  }
  return context;
}

void Simulation::MakeEngine(const Engine::State* state) {
  Engine::Options engine_options;
  // The fixed step, or the adaptive rule's largest: the feasibility check's
  // bound of the fewest steps holds for the whole run.
  engine_options.time_step = scene_.TimeStep(initial_);
  scene_.CheckFeasible(engine_options.time_step);
  if (scene_.adaptive()) {
    time_step_rule_.emplace(scene_.adaptive_time_step, scene_.material, initial_.radii);
  }
  engine_options.skin_fraction = scene_.skin_fraction;
  engine_options.threads = threads_;
  engine_.emplace(initial_, scene_.material, engine_options);
  if (state) {
    if (state->position.size() != initial_.size()) {
      throw InputError(fmt::format("{}: the saved state holds {} particles, its sample {}",
                                   scene_.origin, state->position.size(), initial_.size()));
    }
    // The state carries the Δt it was saved with: a restart continues with
    // it; a fixed-step scene (a fork of a run with another step) takes its
    // own; an adaptive scene re-evaluates at its first step (a stage start).
    engine_->Restore(*state);
    if (!scene_.adaptive()) engine_->SetTimeStep(engine_options.time_step);
  }
}

void Simulation::Setup() {
  initial_ = scene_.BuildSample(&generation_);
  generated_ = scene_.generate.has_value();
  provenance_.start_kind = generated_ ? "generated" : "packing";
  provenance_.start_sha256 = HashPacking(initial_);
  MakeEngine(nullptr);
}

// A scene that starts where another run stopped: the parent's sample (so that
// the engine orders particles and sums the solid volume as the parent did,
// and strains count from the same origin) and its exact engine state.
void Simulation::Fork() {
  const ParentState& parent = *scene_.parent;
  const std::string where = scene_.origin + ": sample.state '" + parent.path + "'";
  if (!std::filesystem::exists(parent.path)) {
    throw InputError(where + " does not exist (give the result file of a granasym DEM run)");
  }
  const Hdf5File file = Hdf5File::OpenRead(parent.path);
  if (!file.Exists(record::kSample) || !file.Exists(record::kSummary)) {
    throw InputError(where + " is not a granasym DEM result file (no /sample or /summary)");
  }
  generated_ = ReadSample(file, &initial_, &generation_);
  const RunSummary summary = ReadSummary(file);
  const std::vector<StageRecord> records = ReadStageRecords(file);
  std::optional<Engine::State> state;
  const bool completed = summary.termination == Termination::kCompleted;
  const bool last = !records.empty() && records.back().name == parent.stage;
  if (parent.stage.empty() || (last && completed && !records.back().end_state)) {
    if (!completed) {
      throw InputError(fmt::format(
          "{}: the run ended '{}' ({}): only a completed run's final state, or the end of one of "
          "its completed stages (sample.stage), can be continued",
          where, ToString(summary.termination), summary.message));
    }
    state = ReadEngineState(file, std::string(record::kFinalState) + "/" + record::kEngineGroup);
  } else {
    std::string names;
    for (const StageRecord& r : records) {
      if (r.failed) continue;
      if (r.name == parent.stage) {
        if (!r.end_state) {
          throw InputError(
              fmt::format("{}: stage '{}' kept no end state (the run had "
                          "output.stage_states = false)",
                          where, parent.stage));
        }
        state = r.end_state;
        break;
      }
      names += (names.empty() ? "" : ", ") + ("'" + r.name + "'");
    }
    if (!state) {
      throw InputError(fmt::format("{}: no completed stage named '{}' (completed stages: {})",
                                   where, parent.stage, names.empty() ? "none" : names));
    }
  }
  provenance_.start_kind = "state";
  provenance_.start_sha256 = HashEngineState(*state);
  provenance_.parent_file = parent.path;
  provenance_.parent_stage = parent.stage;
  if (file.Exists(record::kProvenance)) {
    provenance_.parent_scene_sha256 = ReadProvenance(file).scene_sha256;
  }
  MakeEngine(&*state);
}

void Simulation::StartStage() {
  runner_.stage_started = true;
  StageClock& clock = runner_.clock;
  // A stage that continues the previous one's path keeps the detector's
  // samples, their strains counted from the new stage's start.
  std::vector<AsymptoteDetector::Sample> carried;
  if (runner_.stage > 0 && stage().ContinuesDetection(scene_.stages[runner_.stage - 1])) {
    carried = detector_.samples();
    for (AsymptoteDetector::Sample& sample : carried) sample.strain -= clock.strain_norm;
  }
  clock = StageClock{};
  clock.start_step = engine_->step();
  clock.start_time = engine_->time();
  clock.start_cell = engine_->cell();
  clock.first_row = static_cast<int64_t>(series_.rows());
  detector_ = AsymptoteDetector(stage().asymptote);
  detector_.set_samples(std::move(carried));
  detector_first_row_ = DetectorFirstRow();
  controller_ = stage().spec->MakeController(Context());
  engine_->SetVelocityGradient(controller_->Start());
}

int64_t Simulation::DetectorFirstRow() const {
  const size_t current = static_cast<size_t>(runner_.stage);
  size_t k = current;
  while (k > 0 && k <= records_.size() &&
         scene_.stages[k].ContinuesDetection(scene_.stages[k - 1])) {
    --k;
  }
  return k < current && k < records_.size() ? records_[k].first_row : runner_.clock.first_row;
}

void Simulation::AddRow() {
  const RowMeasures row(*engine_, runner_.stage, initial_.cell, min_diameter_, max_diameter_,
                        histogram_edges_.empty() ? nullptr : &histogram_edges_);
  series_.AddRow(RowValues(row));
  for (int64_t count : row.contacts.histogram)
    histogram_rows_.push_back(static_cast<double>(count));
  runner_.strain_since_output = 0;
  runner_.steps_since_output = 0;
  last_p_kpa_ = row.stress.mean() / kKiloPascal;
  last_psi_deg_ = row.stress.psi() / kDegree;
}

std::optional<std::string> Simulation::LiquefiedStop() {
  const Stage& current = stage();
  if (!current.stop.liquefied) return std::nullopt;
  StageClock& clock = runner_.clock;
  const double p = series_.Last(record::kColumnMeanStress);
  const double z = series_.Last(record::kColumnMechanicalCoordination);
  if (!IsGas(p, z)) {
    clock.gas_since_strain = std::numeric_limits<double>::quiet_NaN();
    return std::nullopt;
  }
  if (std::isnan(clock.gas_since_strain)) clock.gas_since_strain = clock.strain_norm;
  if (clock.strain_norm - clock.gas_since_strain <
      current.stop.liquefied_strain.value_or(current.asymptote.window_strain)) {
    return std::nullopt;
  }
  return fmt::format(
      "liquefied: a gas (p below {:g} kPa or mechanical coordination below {:g}) on every row "
      "over {:.3g} of strain since {:.4g}; now p {:.4g} kPa, Z_m {:.3g}",
      kValidityLimits.gas_mean_stress_kpa, kValidityLimits.gas_mechanical_coordination,
      clock.strain_norm - clock.gas_since_strain, clock.gas_since_strain, p, z);
}

std::optional<std::string> Simulation::CheckRowGuards(bool stage_ends) {
  const ValidityLimits& limits = kValidityLimits;
  const int64_t step = engine_->step();
  const double overlap = series_.Last(record::kColumnOverlapMax);
  const double p = series_.Last(record::kColumnMeanStress);
  // e <= 0 first: when both hold, it names the impossibility.
  const double e = series_.Last(record::kColumnVoidRatio);
  if (!(e > 0)) {
    return fmt::format(
        "void ratio e = {:.4g} <= 0 at step {} (p = {:.4g} kPa): the cell is smaller than the "
        "solid volume; overlaps no longer describe contacts (contacts too soft for this p)",
        e, step, p);
  }
  if (overlap >= limits.overlap_failure) {
    return fmt::format(
        "relative overlap {:.3g} at step {} (p = {:.4g} kPa) reached the contact limit {:g}: "
        "spheres interpenetrate (loading too fast, time step too large, or p too high for the "
        "contact stiffness)",
        overlap, step, p, limits.overlap_failure);
  }
  // A mean-stress target the stage moves away from: once the sample is not
  // a gas, the closest approach is tracked; stale for unreachable_strain of
  // strain, the target cannot be reached.
  const StopConditions& stop = stage().stop;
  if (!stop.mean_stress_kpa || stage_ends) return std::nullopt;
  StageClock& clock = runner_.clock;
  const double target = *stop.mean_stress_kpa;
  const Direction direction = MeanStressDirection(stop, clock);
  const double z = series_.Last(record::kColumnMechanicalCoordination);
  if (!IsGas(p, z, limits)) {
    const double distance =
        direction == Direction::kRising ? std::log(target / p) : std::log(p / target);
    if (distance < clock.target_distance) {
      clock.target_distance = distance;
      clock.target_distance_strain = clock.strain_norm;
      return std::nullopt;
    }
  }
  if (std::isfinite(clock.target_distance) &&
      clock.strain_norm - clock.target_distance_strain >= limits.unreachable_strain) {
    const double closest = direction == Direction::kRising
                               ? target * std::exp(-clock.target_distance)
                               : target * std::exp(clock.target_distance);
    return fmt::format(
        "stage '{}' cannot reach its mean-stress target {:.6g} kPa ({}): p has moved away from "
        "it for {:.3g} of strain, from its closest {:.4g} kPa at stage strain {:.4g} to {:.4g} "
        "kPa at {:.4g}{}",
        stage().name, target, ToString(direction), clock.strain_norm - clock.target_distance_strain,
        closest, clock.target_distance_strain, p, clock.strain_norm,
        IsGas(p, z, limits) ? fmt::format(" (a gas: mechanical coordination {:.3g})", z) : "");
  }
  return std::nullopt;
}

namespace {

// The first of the stage's rows [first, last] at or after `time` (the
// window's start); `last` when none.
int64_t FirstRowAfter(const TimeSeries& series, int64_t first, int64_t last, double time) {
  const auto& times = series.Values(record::kColumnTime);
  for (int64_t k = first; k <= last; ++k) {
    if (times[k] >= time) return k;
  }
  return last;
}

}  // namespace

void Simulation::FinishStage(const std::string& reason, bool failed) {
  StageRecord record;
  record.name = stage().name;
  record.type = stage().type();
  record.first_row = runner_.clock.first_row;
  record.last_row = static_cast<int64_t>(series_.rows()) - 1;
  record.stop_reason = reason;
  record.failed = failed;
  const bool has_rows = record.last_row >= record.first_row;
  const bool detect = stage().detect_asymptote;
  const AsymptoteDetector::Result result =
      detect ? detector_.Evaluate() : AsymptoteDetector::Result{};
  // The state: the window's rows when a full window exists, else the last row.
  const bool window = detect && result.window_strain > 0;
  RowState state;
  if (has_rows) {
    const int64_t state_row = window ? FirstRowAfter(series_, detector_first_row_, record.last_row,
                                                     result.window_start_time)
                                     : record.last_row;
    state = RowState::Mean(series_, state_row, record.last_row);
    record.validity = StageValidity::FromRows(series_, record.first_row, record.last_row, state);
  }
  if (detect) {
    AsymptoteRecord a;
    a.path_kind = stage().asymptote.kind;
    a.criterion = stage().asymptote;
    a.window_strain = result.window_strain;
    a.window_lnp = result.window_lnp;
    if (window) {
      a.mean_stress_kpa = result.mean_stress_kpa;
      a.void_ratio = result.void_ratio;
      a.psi_sigma_deg = result.psi_sigma / kDegree;
      a.psi_epsilon_deg = result.psi_epsilon / kDegree;
      a.q_over_p = result.q_over_p;
    } else if (has_rows) {
      a.mean_stress_kpa = series_.Last(record::kColumnMeanStress);
      a.void_ratio = series_.Last(record::kColumnVoidRatio);
      a.psi_sigma_deg = series_.Last(record::kColumnPsiSigma);
      a.psi_epsilon_deg = series_.Last(record::kColumnPsiEpsilon);
      a.q_over_p = 3.0 / std::sqrt(2.0) * std::tan(a.psi_sigma_deg * kDegree);
    }
    a.coordination = state.coordination;
    a.mechanical_coordination = state.mechanical_coordination;
    a.inertial_number_dmin = state.inertial_number_dmin;
    a.inertial_number_dmax = state.inertial_number_dmax;
    a.max_relative_overlap = state.max_relative_overlap;
    a.psi_change_deg = result.psi_change_deg;
    a.lnp_change = result.lnp_change;
    a.lnp_half_difference = result.lnp_half_difference;
    a.slope_change = result.slope_change;
    a.psi_epsilon_change_deg = result.psi_epsilon_change_deg;
    a.lnv_change = result.lnv_change;
    a.dlnp_dstrain = result.slope_lnp;
    a.dln1pe_dlnp = result.slope_lnv_lnp;
    const ValidityLimits& limits = kValidityLimits;
    if (failed || !has_rows || state.max_relative_overlap > limits.overlap_unreliable) {
      a.status = AsymptoteStatus::kInvalid;
    } else if (IsGas(state.mean_stress_kpa, state.mechanical_coordination, limits)) {
      a.status = AsymptoteStatus::kGas;
    } else {
      a.status = result.status;
    }
    a.detected = a.status == AsymptoteStatus::kDetected;
    if (result.detected() && !a.detected) {
      record.stop_reason += fmt::format("; not an asymptote: status {} ({})", ToString(a.status),
                                        EnumDescription(a.status));
    }
    record.asymptote = a;
    record.asymptote_criterion = stage().asymptote.Describe();
  }
  const bool last = runner_.stage + 1 == static_cast<int64_t>(scene_.stages.size());
  if (scene_.output.stage_states && !last && !failed) record.end_state = engine_->Save();
  Log(fmt::format("stage {} '{}' {} after {} steps: {}", runner_.stage + 1, stage().name,
                  failed ? "failed" : "done", runner_.clock.steps(*engine_), record.stop_reason));
  Log(fmt::format("  validity: {}", record.validity.OneLine()));
  if (record.asymptote) {
    const AsymptoteRecord& a = *record.asymptote;
    Log(fmt::format(
        "  asymptote ({}): {}; p {:.4g} kPa, e {:.4f}, psi_sigma {:.2f} deg, psi_epsilon {:.2f} "
        "deg over a window of {:.3g} strain and {:.3g} of ln p",
        ToString(a.path_kind), ToString(a.status), a.mean_stress_kpa, a.void_ratio, a.psi_sigma_deg,
        a.psi_epsilon_deg, a.window_strain, a.window_lnp));
  }
  records_.push_back(std::move(record));
  ++runner_.stage;
  runner_.stage_started = false;
  controller_.reset();
}

std::string RunProgressEta(double eta_seconds) {
  return eta_seconds < 0 ? "?" : fmt::format("{:.0f}s", eta_seconds);
}

void Simulation::ReportProgress() {
  if (!options_.progress || since_progress_.Seconds() < options_.progress_period_s) return;
  since_progress_ = Stopwatch();
  const StopConditions& stop = stage().stop;
  const StageClock& clock = runner_.clock;
  // Fraction of the stage done, from the stop condition closest to completion.
  double fraction = 0;
  if (stop.steps) fraction = std::max(fraction, double(clock.steps(*engine_)) / *stop.steps);
  if (stop.time_s)
    fraction = std::max(fraction, (engine_->time() - clock.start_time) / *stop.time_s);
  if (stop.strain_norm) fraction = std::max(fraction, clock.strain_norm / *stop.strain_norm);
  // From a contact-free start, progress in ln p counts from the first
  // positive pressure seen in the stage.
  if (eta_stage_ != runner_.stage) {
    eta_stage_ = runner_.stage;
    eta_p0_ = clock.start_p_kpa;
  }
  if (!(eta_p0_ > 0) && last_p_kpa_ > 0) eta_p0_ = last_p_kpa_;
  if (stop.mean_stress_kpa && last_p_kpa_ > 0 && eta_p0_ > 0) {
    const double done = std::log(last_p_kpa_ / eta_p0_);
    const double total = std::log(*stop.mean_stress_kpa / eta_p0_);
    if (total != 0) fraction = std::max(fraction, done / total);
  }
  RunProgress progress;
  progress.stage = runner_.stage;
  progress.stages = static_cast<int64_t>(scene_.stages.size());
  progress.stage_name = stage().name;
  progress.step = engine_->step();
  const double seconds = stage_clock_.Seconds();
  progress.steps_per_second =
      static_cast<double>(engine_->step() - stage_clock_start_step_) / std::max(1e-9, seconds);
  if (fraction > 1e-3 && fraction < 1) progress.eta_seconds = seconds * (1 - fraction) / fraction;
  progress.mean_stress_kpa = last_p_kpa_;
  progress.void_ratio = engine_->void_ratio();
  progress.psi_sigma_deg = last_psi_deg_;
  options_.progress(progress);
}

void Simulation::WriteResults(const RunSummary& summary) const {
  Hdf5File file = Hdf5File::CreateAtomic(options_.output_path);
  file.WriteString(record::kScene, scene_.text);
  file.SetAttribute(record::kScene, record::kSceneOrigin, scene_.origin);
  WriteProvenance(file, provenance_);
  series_.Write(file, record::kSeries);
  WriteHistograms(file, histogram_edges_, histogram_rows_);
  WriteStageRecords(file, records_, scene_.stages, threads_);
  WriteSummary(file, summary, ComputeContactDurations(initial_.radii, scene_.material));
  WriteFinalState(file, *engine_, threads_);
  WriteSample(file, initial_, generated_ ? &generation_ : nullptr);
  file.Commit();
}

void Simulation::WriteCheckpoint() {
  Hdf5File file = Hdf5File::CreateAtomic(options_.output_path + ".ckpt");
  file.WriteString(record::kScene, scene_.text);
  WriteProvenance(file, provenance_);
  WriteSample(file, initial_, generated_ ? &generation_ : nullptr);
  WriteEngineState(file, record::kEngine, engine_->Save(), threads_);
  RunnerRecord runner = runner_;
  if (controller_) runner.controller_state = controller_->SaveState();
  runner.detector_samples = detector_.samples();
  WriteRunner(file, runner);
  WriteStageRecords(file, records_, scene_.stages, threads_);
  series_.Write(file, record::kSeries);
  WriteHistograms(file, histogram_edges_, histogram_rows_);
  file.Commit();
  checkpoint_step_ = engine_->step();
  checkpoint_at_end_ = done();
}

void Simulation::FailWriting(const FileError& error) const {
  const std::string checkpoint = options_.output_path + ".ckpt";
  if (checkpoint_step_ < 0) {
    throw FileError(std::string(error.what()) +
                    "; no checkpoint had been written (the run was shorter than "
                    "output.checkpoint_interval_s): make space and run it again");
  }
  throw FileError(fmt::format(
      "{}; nothing computed up to step {} is lost: the checkpoint '{}' of that step is kept{} "
      "(make space, then continue with `granasym dem run {} --out {} --restart`)",
      error.what(), checkpoint_step_, checkpoint,
      checkpoint_at_end_ ? ", the run's end: a restart only writes the results" : "", scene_.origin,
      options_.output_path));
}

void Simulation::LoadCheckpoint() {
  const std::string path = options_.output_path + ".ckpt";
  if (!std::filesystem::exists(path)) {
    throw InputError("--restart: no checkpoint '" + path +
                     "' (it is written next to --out during a run)");
  }
  const Hdf5File file = Hdf5File::OpenRead(path);
  const Provenance saved = ReadProvenance(file);
  if (saved.scene_sha256 != provenance_.scene_sha256) {
    throw InputError("--restart: the scene '" + scene_.origin +
                     "' differs from the scene of the checkpoint '" + path +
                     "': restart with the same scene");
  }
  provenance_.start_kind = saved.start_kind;
  provenance_.start_sha256 = saved.start_sha256;
  provenance_.parent_file = saved.parent_file;
  provenance_.parent_stage = saved.parent_stage;
  provenance_.parent_scene_sha256 = saved.parent_scene_sha256;
  generated_ = ReadSample(file, &initial_, &generation_);
  int threads = 0;
  const Engine::State state = ReadEngineState(file, record::kEngine, &threads);
  if (threads != threads_) {
    Log(
        fmt::format("warning: the checkpoint was written with {} threads, continuing with {}: the "
                    "result will not be bit-identical to an uninterrupted run",
                    threads, threads_));
  }
  runner_ = ReadRunner(file);
  records_ = ReadStageRecords(file);
  series_ = TimeSeries::Read(file, record::kSeries);
  histogram_rows_ = ReadHistogramRows(file);
  CheckCheckpoint(path);
  MakeEngine(&state);
  checkpoint_step_ = state.step;
  checkpoint_at_end_ = done();
  if (!done()) {
    detector_ = AsymptoteDetector(stage().asymptote);
    detector_.set_samples(runner_.detector_samples);
    detector_first_row_ = DetectorFirstRow();
    if (runner_.stage_started) {
      controller_ = stage().spec->MakeController(Context());
      try {
        controller_->RestoreState(runner_.controller_state);
      } catch (const std::out_of_range&) {
        throw InputError(fmt::format(
            "{}: dataset {}/controller_state holds {} values, too few for stage '{}' (the file "
            "is corrupt, or not written by granasym)",
            path, record::kRunner, runner_.controller_state.size(), stage().name));
      }
    }
  }
}

// The runner's record against the scene and the series, before anything
// indexes with it (ReadEngineState checks the engine state).
void Simulation::CheckCheckpoint(const std::string& path) const {
  const auto invalid = [&path](const std::string& what) {
    throw InputError(path + ": " + what + " (the file is corrupt, or not written by granasym)");
  };
  const int64_t stages = static_cast<int64_t>(scene_.stages.size());
  const int64_t rows = static_cast<int64_t>(series_.rows());
  if (runner_.stage < 0 || runner_.stage > stages) {
    invalid(fmt::format("{} attribute stage = {} is not a stage of the scene's {}", record::kRunner,
                        runner_.stage, stages));
  }
  if (static_cast<int64_t>(records_.size()) != runner_.stage) {
    invalid(fmt::format("{} holds {} stage records for the {} stages done ({} attribute stage)",
                        record::kStages, records_.size(), runner_.stage, record::kRunner));
  }
  for (size_t k = 0; k < records_.size(); ++k) {
    const StageRecord& r = records_[k];
    if (r.first_row < 0 || r.first_row > rows || r.last_row < r.first_row - 1 ||
        r.last_row >= rows) {
      invalid(fmt::format("{} spans rows {}..{} of a series of {}", StageGroup(k), r.first_row,
                          r.last_row, rows));
    }
  }
  if (runner_.clock.first_row < 0 || runner_.clock.first_row > rows) {
    invalid(fmt::format("{} attribute stage_first_row = {} lies beyond the series' {} rows",
                        record::kRunner, runner_.clock.first_row, rows));
  }
  std::vector<std::string> expected, stored;
  for (const TimeSeries::Column& column : SeriesColumns()) expected.push_back(column.name);
  for (const TimeSeries::Column& column : series_.columns()) stored.push_back(column.name);
  if (stored != expected) {
    invalid(
        fmt::format("{} holds {} columns, this granasym writes {}: a checkpoint of another "
                    "version cannot be continued",
                    record::kSeries, stored.size(), expected.size()));
  }
  const size_t bins = scene_.output.overlap_histogram ? scene_.output.histogram_bins : 0;
  if (histogram_rows_.size() != bins * series_.rows()) {
    invalid(fmt::format("{}/counts holds {} counts for {} rows of {} bins",
                        record::kSeriesHistogram, histogram_rows_.size(), series_.rows(), bins));
  }
}

RunSummary Simulation::Finish(RunSummary& summary, Termination termination,
                              const std::string& message, double loop_seconds, int64_t first_step,
                              const Stopwatch& wall) {
  summary.termination = termination;
  summary.message = message;
  summary.steps = engine_->step();
  summary.simulated_time = engine_->time();
  summary.loop_seconds = loop_seconds;
  summary.wall_seconds = wall.Seconds();
  summary.particle_steps_per_second =
      loop_seconds > 0 ? double(engine_->step() - first_step) * engine_->size() / loop_seconds : 0;
  summary.neighbor_builds = engine_->neighbors().builds();
  summary.rows = static_cast<int64_t>(series_.rows());
  summary.stages_completed = static_cast<int64_t>(records_.size());
  SummarizeTimeSteps(series_, &summary);
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
  summary.validity.clear();
  for (const StageRecord& r : records_) {
    if (r.validity.flags.empty()) continue;
    summary.validity += fmt::format("{}stage '{}': {}", summary.validity.empty() ? "" : "; ",
                                    r.name, r.validity.FlagNames());
  }
  if (!summary.validity.empty()) Log("validity: " + summary.validity);
  try {
    WriteResults(summary);
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
    std::filesystem::remove(options_.output_path + ".ckpt");
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
  provenance_.program_version = ProgramVersion();
  provenance_.scene_canonical = scene_.Canonical();
  provenance_.scene_sha256 = Sha256Hex(provenance_.scene_canonical);
  provenance_.threads = threads_;
  provenance_.cpu_model = HostCpuModel();
  if (options_.restart) {
    LoadCheckpoint();
  } else if (scene_.parent) {
    Fork();
  } else {
    Setup();
    if (generated_) Log(generation_.Table());
  }
  const StageContext sizes = Context();
  min_diameter_ = sizes.min_diameter;
  max_diameter_ = sizes.max_diameter;
  if (scene_.output.overlap_histogram) {
    histogram_edges_ = LogarithmicEdges(scene_.output.histogram_min, scene_.output.histogram_max,
                                        scene_.output.histogram_bins);
  }
  const ContactDurations d = ComputeContactDurations(initial_.radii, scene_.material);
  Log(fmt::format(
      "{} spheres, {} threads; time step {:.4g} s = {:.3f} of the smallest contact "
      "duration {:.4g} s (reduced mass; {:.4g} s with one sphere's mass; largest "
      "{:.4g} / {:.4g} s); stability limit {:.4g} s",
      initial_.size(), threads_, engine_->time_step(),
      engine_->time_step() / d.smallest_reduced_mass, d.smallest_reduced_mass,
      d.smallest_single_mass, d.largest_reduced_mass, d.largest_single_mass, d.critical_time_step));
  const std::string time_step_rule = time_step_rule_ ? time_step_rule_->Describe() : "fixed";
  Log("time step " + time_step_rule);
  const Material& material = scene_.material;
  if (material.stiffness_scaling != 1) {
    Log(fmt::format(
        "stiffness scaling {:g}: the contacts use E = {:.6g} MPa (of the grains' {:.6g} MPa); "
        "the stiffness number kappa falls with it",
        material.stiffness_scaling, material.contact_modulus() * 1e-6,
        material.youngs_modulus * 1e-6));
  }
  RunSummary summary;
  summary.particles = static_cast<int64_t>(engine_->size());
  summary.threads = threads_;
  summary.time_step = engine_->time_step();
  summary.time_step_rule = time_step_rule;
  summary.stiffness_scaling = material.stiffness_scaling;
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

// One iteration per step: measure what is due, let the controller act on
// it, check the stops, write the row, then advance (or end the stage there).
Simulation::Outcome Simulation::Loop(const RunSummary& summary, double& loop_seconds) {
  Stopwatch since_checkpoint;
  const OutputOptions& output = scene_.output;
  while (!done()) {
    Stopwatch step_clock;
    if (!runner_.stage_started) {
      StartStage();
      stage_clock_ = Stopwatch();
      stage_clock_start_step_ = engine_->step();
    }
    const Stage& current = stage();
    StageClock& clock = runner_.clock;
    const int64_t stage_steps = clock.steps(*engine_);
    const bool strain_stop = StrainOrDurationStopReached(current.stop, clock, *engine_);
    const bool output_due =
        series_.rows() == 0 || stage_steps == 0 ||
        runner_.strain_since_output >= output.interval_strain * (1 - 1e-9) ||
        (output.interval_steps > 0 && runner_.steps_since_output >= output.interval_steps);
    const bool sample_due =
        current.detect_asymptote && clock.strain_norm >= clock.next_sample_strain;
    const bool need_stress =
        output_due || sample_due || strain_stop || controller_->NeedsStress(stage_steps) ||
        current.stop.mean_stress_kpa.has_value() || std::isnan(clock.start_p_kpa);
    const bool retime = time_step_rule_ && time_step_rule_->Due(stage_steps);
    // The strain of the step just taken (of length dt), on the stage's clocks.
    auto count_step = [&](double dt) {
      const auto& g = engine_->velocity_gradient();
      const double increment = dt * std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
      clock.strain_norm += increment;
      runner_.strain_since_output += increment;
      ++runner_.steps_since_output;
    };
    if (!need_stress && !retime) {
      // Nothing is measured, controlled, stopped, written or re-timed at this
      // step: forces, kick and drift in one pass (Engine::Step, bit-identical
      // to ComputeForces + Integrate).
      const double dt = engine_->time_step();
      engine_->Step({});
      count_step(dt);
    } else {
      engine_->ComputeForces({need_stress, controller_->NeedsStiffness()});
      // The adaptive Δt from the contacts just evaluated, before anything uses
      // this step's Δt: the controller's rate, the step itself, its strain.
      if (retime) {
        const double next = time_step_rule_->Evaluate(*engine_);
        if (next != engine_->time_step()) engine_->SetTimeStep(next);
      }
      const double dt = engine_->time_step();
      double p = std::numeric_limits<double>::quiet_NaN();
      if (need_stress) {
        p = MeanStressKpa(engine_->sums());
        if (!std::isfinite(p)) {
          loop_seconds += step_clock.Seconds();
          return Outcome{
              Termination::kFailed,
              fmt::format("non-finite stress at step {}: the motion became unstable (time "
                          "step {:.3g} s too large for the contact stiffness?)",
                          engine_->step(), dt)};
        }
        if (std::isnan(clock.start_p_kpa)) clock.start_p_kpa = p;
        if (const auto gradient = controller_->Control(engine_->sums(), dt)) {
          engine_->SetVelocityGradient(*gradient);
        }
      }
      std::optional<std::string> reason;
      if (sample_due) {
        const AxisymmetricStress stress = AxisymmetricFromTensor(engine_->sums().stress);
        const double p_kpa = stress.mean() / kKiloPascal;
        const auto& cell = engine_->cell();
        const auto& reference = initial_.cell;
        detector_.Add({clock.strain_norm, stress.psi(),
                       p_kpa > 0 ? std::log(p_kpa) : std::numeric_limits<double>::quiet_NaN(),
                       std::log1p(engine_->void_ratio()), -std::log(cell[0] / reference[0]),
                       -0.5 * (std::log(cell[1] / reference[1]) + std::log(cell[2] / reference[2])),
                       engine_->time()});
        clock.next_sample_strain += current.asymptote.sample_strain;
      }
      if (need_stress) reason = MeanStressStop(current.stop, clock, p);
      if (!reason && sample_due && current.stop.asymptote) {
        const AsymptoteDetector::Result result = detector_.Evaluate();
        // A gas, or a state with overlaps beyond the reliable, is no asymptote:
        // the stage goes on (a compression path leaves a loose start behind).
        const int64_t last_row = static_cast<int64_t>(series_.rows()) - 1;
        bool valid = result.detected() && last_row >= clock.first_row;
        if (valid) {
          const RowState state = RowState::Mean(
              series_,
              FirstRowAfter(series_, detector_first_row_, last_row, result.window_start_time),
              last_row);
          valid = !IsGas(result.mean_stress_kpa, state.mechanical_coordination) &&
                  state.max_relative_overlap <= kValidityLimits.overlap_unreliable;
        }
        if (valid) {
          reason = fmt::format(
              "asymptotic state detected ({}: p {:.4g} kPa, psi_sigma {:.3f} deg over {:.3g} of "
              "strain and {:.3g} of ln p)",
              ToString(current.asymptote.kind), result.mean_stress_kpa, result.psi_sigma / kDegree,
              result.window_strain, result.window_lnp);
        }
      }
      if (!reason && need_stress) reason = controller_->CheckStop(*engine_, stage_steps);
      if (!reason && strain_stop) reason = StrainOrDurationReason(current.stop, clock, *engine_);
      if (output_due || reason) {
        AddRow();
        if (const std::optional<std::string> failure = CheckRowGuards(reason.has_value())) {
          loop_seconds += step_clock.Seconds();
          return Outcome{Termination::kFailed, *failure};
        }
        if (!reason) reason = LiquefiedStop();
      }
      if (reason) {
        // The stage ends at the state that met its condition (its last row);
        // the next stage starts from the same state: the engine re-evaluates
        // its forces there without advancing the shear history.
        FinishStage(*reason);
      } else {
        engine_->Integrate();
        count_step(dt);
      }
    }
    loop_seconds += step_clock.Seconds();

    if (!done()) ReportProgress();
    if (options_.stop_requested && options_.stop_requested(engine_->step())) {
      return Outcome{
          Termination::kInterrupted,
          fmt::format("interrupted at step {}; continue with --restart", engine_->step())};
    }
    if ((engine_->step() & 255) == 0 &&
        since_checkpoint.Seconds() >= output.checkpoint_interval_s) {
      WriteCheckpoint();
      RunSummary partial = summary;
      partial.termination = Termination::kInterrupted;
      partial.message = "run in progress (partial results at the last checkpoint)";
      partial.steps = engine_->step();
      partial.simulated_time = engine_->time();
      partial.rows = static_cast<int64_t>(series_.rows());
      partial.stages_completed = static_cast<int64_t>(records_.size());
      SummarizeTimeSteps(series_, &partial);
      WriteResults(partial);
      since_checkpoint = Stopwatch();
    }
  }
  return Outcome{Termination::kCompleted, "all stages completed"};
}

}  // namespace

std::string RunProgress::OneLine() const {
  return fmt::format(
      "stage {}/{} '{}' | step {} | {:.0f} steps/s | ETA {} | p {:.4g} kPa | e {:.4f} "
      "| psi_sigma {:.2f} deg",
      stage + 1, stages, stage_name, step, steps_per_second, RunProgressEta(eta_seconds),
      mean_stress_kpa, void_ratio, psi_sigma_deg);
}

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

Packing ReadResultPacking(const std::string& result_path, const std::string& group) {
  const Hdf5File file = Hdf5File::OpenRead(result_path);
  // As a text packing: what is exported must be readable (restarts read
  // their sample through ReadSample, unchecked, so they never break here).
  Packing packing = ReadPacking(file, group);
  packing.Validate(result_path + ":" + group);
  return packing;
}

}  // namespace granasym::dem
