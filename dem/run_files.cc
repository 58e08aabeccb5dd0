#include "dem/run_files.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "common/hdf5_file.h"
#include "dem/run_record_names.h"

namespace granasym::dem {
namespace {

// The runner's record against the scene and the rows, before anything
// indexes with it (ReadEngineState checks the engine state).
void CheckRunner(const std::string& path, const Scene& scene, const RunnerRecord& runner,
                 const RunContents& contents) {
  const auto invalid = [&path](const std::string& what) {
    throw InputError(path + ": " + what + " (the file is corrupt, or not written by granasym)");
  };
  const int64_t stages = static_cast<int64_t>(scene.stages.size());
  const int64_t rows = static_cast<int64_t>(contents.series.rows());
  if (runner.stage < 0 || runner.stage > stages) {
    invalid(fmt::format("{} attribute stage = {} is not a stage of the scene's {}", record::kRunner,
                        runner.stage, stages));
  }
  if (static_cast<int64_t>(contents.stages.size()) != runner.stage) {
    invalid(fmt::format("{} holds {} stage records for the {} stages done ({} attribute stage)",
                        record::kStages, contents.stages.size(), runner.stage, record::kRunner));
  }
  for (size_t k = 0; k < contents.stages.size(); ++k) {
    const StageRecord& r = contents.stages[k];
    if (r.first_row < 0 || r.first_row > rows || r.last_row < r.first_row - 1 ||
        r.last_row >= rows) {
      invalid(fmt::format("{} spans rows {}..{} of a series of {}", StageGroup(k), r.first_row,
                          r.last_row, rows));
    }
  }
  if (runner.clock.first_row < 0 || runner.clock.first_row > rows) {
    invalid(fmt::format("{} attribute stage_first_row = {} lies beyond the series' {} rows",
                        record::kRunner, runner.clock.first_row, rows));
  }
  std::vector<std::string> expected, stored;
  for (const TimeSeries::Column& column : SeriesColumns()) expected.push_back(column.name);
  for (const TimeSeries::Column& column : contents.series.columns()) {
    stored.push_back(column.name);
  }
  if (stored != expected) {
    invalid(
        fmt::format("{} holds {} columns, this granasym writes {}: a checkpoint of another "
                    "version cannot be continued",
                    record::kSeries, stored.size(), expected.size()));
  }
  const size_t bins = scene.output.overlap_histogram ? scene.output.histogram_bins : 0;
  if (contents.histogram_rows.size() != bins * contents.series.rows()) {
    invalid(fmt::format("{}/counts holds {} counts for {} rows of {} bins",
                        record::kSeriesHistogram, contents.histogram_rows.size(),
                        contents.series.rows(), bins));
  }
}

}  // namespace

std::string CheckpointPath(const std::string& output_path) { return output_path + ".ckpt"; }

void WriteResult(const std::string& path, const Scene& scene, const RunContents& contents,
                 const RunSummary& summary, const Engine& engine, int threads) {
  Hdf5File file = Hdf5File::CreateAtomic(path);
  file.WriteString(record::kScene, scene.text);
  file.SetAttribute(record::kScene, record::kSceneOrigin, scene.origin);
  WriteProvenance(file, contents.provenance);
  contents.series.Write(file, record::kSeries);
  WriteHistograms(file, contents.histogram_edges, contents.histogram_rows);
  WriteStageRecords(file, contents.stages, scene.stages, threads);
  WriteSummary(file, summary, ComputeContactDurations(contents.sample.radii, scene.material));
  WriteFinalState(file, engine, threads);
  WriteSample(file, contents.sample, contents.generated ? &contents.generation : nullptr);
  file.Commit();
}

void WriteCheckpoint(const std::string& path, const Scene& scene, const RunContents& contents,
                     const Engine& engine, int threads, const RunnerRecord& runner) {
  Hdf5File file = Hdf5File::CreateAtomic(path);
  file.WriteString(record::kScene, scene.text);
  WriteProvenance(file, contents.provenance);
  WriteSample(file, contents.sample, contents.generated ? &contents.generation : nullptr);
  WriteEngineState(file, record::kEngine, engine.Save(), threads);
  WriteRunner(file, runner);
  WriteStageRecords(file, contents.stages, scene.stages, threads);
  contents.series.Write(file, record::kSeries);
  WriteHistograms(file, contents.histogram_edges, contents.histogram_rows);
  file.Commit();
}

CheckpointState ReadCheckpoint(const std::string& path, const Scene& scene, int threads,
                               const std::function<void(const std::string&)>& log,
                               RunContents* contents) {
  if (!std::filesystem::exists(path)) {
    throw InputError("--restart: no checkpoint '" + path +
                     "' (it is written next to --out during a run)");
  }
  const Hdf5File file = Hdf5File::OpenRead(path);
  const Provenance saved = ReadProvenance(file);
  Provenance& provenance = contents->provenance;
  if (saved.scene_sha256 != provenance.scene_sha256) {
    throw InputError("--restart: the scene '" + scene.origin +
                     "' differs from the scene of the checkpoint '" + path +
                     "': restart with the same scene");
  }
  provenance.start_kind = saved.start_kind;
  provenance.start_sha256 = saved.start_sha256;
  provenance.parent_file = saved.parent_file;
  provenance.parent_stage = saved.parent_stage;
  provenance.parent_scene_sha256 = saved.parent_scene_sha256;
  contents->generated = ReadSample(file, &contents->sample, &contents->generation);
  CheckpointState state;
  state.engine = ReadEngineState(file, record::kEngine, &state.threads);
  if (state.threads != threads && log) {
    log(fmt::format(
        "warning: the checkpoint was written with {} threads, continuing with {}: the result "
        "will not be bit-identical to an uninterrupted run",
        state.threads, threads));
  }
  state.runner = ReadRunner(file);
  contents->stages = ReadStageRecords(file);
  contents->series = TimeSeries::Read(file, record::kSeries);
  contents->histogram_rows = ReadHistogramRows(file);
  CheckRunner(path, scene, state.runner, *contents);
  return state;
}

void ThrowWritingFailure(const FileError& error, const KeptCheckpoint& kept, const Scene& scene,
                         const std::string& output_path) {
  if (kept.step < 0) {
    throw FileError(std::string(error.what()) +
                    "; no checkpoint had been written (the run was shorter than "
                    "output.checkpoint_interval_s): make space and run it again");
  }
  throw FileError(fmt::format(
      "{}; nothing computed up to step {} is lost: the checkpoint '{}' of that step is kept{} "
      "(make space, then continue with `granasym dem run {} --out {} --restart`)",
      error.what(), kept.step, CheckpointPath(output_path),
      kept.at_end ? ", the run's end: a restart only writes the results" : "", scene.origin,
      output_path));
}

void SummarizeRun(const RunContents& contents, const Engine& engine, RunSummary* summary) {
  summary->steps = engine.step();
  summary->simulated_time = engine.time();
  const TimeSeries& series = contents.series;
  summary->rows = static_cast<int64_t>(series.rows());
  summary->stages_completed = static_cast<int64_t>(contents.stages.size());
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

std::string ValiditySummary(const std::vector<StageRecord>& stages) {
  std::string summary;
  for (const StageRecord& r : stages) {
    if (r.validity.flags.empty()) continue;
    summary += fmt::format("{}stage '{}': {}", summary.empty() ? "" : "; ", r.name,
                           r.validity.FlagNames());
  }
  return summary;
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
