// Runs, blocking: a scene (dem::RunScene) and a programme (study::RunStudy,
// then the study's tables as after `granasym study run`), with Python
// callbacks for progress and log lines. The GIL is released while the C++
// runs and taken again in each callback. A callback that raises, or Ctrl-C
// (checked at each progress report), stops the run as a signal stops the
// program (results so far and a checkpoint kept) and the exception is
// raised when the run has stopped.
#include <fmt/format.h>
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "analysis/study_tables.h"
#include "common/error.h"
#include "common/output_path.h"
#include "common/provenance.h"
#include "dem/packing.h"
#include "dem/run_progress.h"
#include "dem/run_record.h"
#include "dem/scene.h"
#include "dem/simulation.h"
#include "python/bindings.h"
#include "study/parallelism.h"
#include "study/plan.h"
#include "study/programme.h"
#include "study/runner.h"

namespace py = pybind11;

namespace granasym::python {

py::dict SummaryDict(const dem::RunSummary& summary);  // python/results.cc

namespace {

// What a progress callback gets: a scene's state, and a study's.
py::dict ProgressDict(const dem::RunProgress& state) {
  py::dict d;
  d["stage"] = state.stage;
  d["stages"] = state.stages;
  d["stage_name"] = state.stage_name;
  d["step"] = state.step;
  d["steps_per_second"] = state.steps_per_second;
  d["eta_s"] = state.eta_seconds;
  d["p_kpa"] = state.mean_stress_kpa;
  d["e"] = state.void_ratio;
  d["psi_sigma_deg"] = state.psi_sigma_deg;
  d["line"] = state.OneLine();
  return d;
}

py::dict ProgressDict(const study::StudyProgress& state) {
  py::dict d;
  d["total"] = state.total;
  d["done"] = state.done;
  d["running"] = state.running;
  d["left"] = state.left;
  d["failed"] = state.failed;
  d["cached"] = state.cached;
  d["particle_steps_per_second"] = state.particle_steps_per_second;
  d["eta_s"] = state.eta_seconds;
  d["line"] = state.OneLine();
  return d;
}

// The Python side of a run: its callbacks, the first exception one raised
// (or a pending Ctrl-C), and the stop request that follows it. Callbacks
// come from the C++ threads with the GIL released; each takes the GIL.
class Callbacks {
 public:
  Callbacks(py::object progress, py::object log)
      : progress_(std::move(progress)), log_(std::move(log)) {}
  ~Callbacks() {
    // The callables are released with the GIL held (the run has returned).
    py::gil_scoped_acquire gil;
    progress_ = py::object();
    log_ = py::object();
  }

  bool stop() const { return stop_.load(); }

  // Hands `options`' progress (as ProgressDict) and log lines to the callables.
  template <typename State, typename Options>
  void Connect(Options* options) {
    options->progress = [this](const State& state) {
      Progress([&state] { return ProgressDict(state); });
    };
    options->log = [this](const std::string& line) { Log(line); };
  }

  // Calls `make_argument` and the progress callable with it; checks for Ctrl-C.
  template <typename MakeArgument>
  void Progress(const MakeArgument& make_argument) {
    py::gil_scoped_acquire gil;
    std::lock_guard<std::mutex> lock(mutex_);
    if (error_) return;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (!progress_.is_none()) progress_(make_argument());
    } catch (py::error_already_set& e) {
      error_ = std::make_unique<py::error_already_set>(std::move(e));
      stop_ = true;
    }
  }

  void Log(const std::string& line) {
    py::gil_scoped_acquire gil;
    std::lock_guard<std::mutex> lock(mutex_);
    if (error_ || log_.is_none()) return;
    try {
      log_(line);
    } catch (py::error_already_set& e) {
      error_ = std::make_unique<py::error_already_set>(std::move(e));
      stop_ = true;
    }
  }

  // After the run, with the GIL: raises what a callback raised.
  void Rethrow() {
    if (error_) {
      py::error_already_set error = std::move(*error_);
      error_.reset();
      throw error;
    }
  }

 private:
  py::object progress_, log_;
  std::mutex mutex_;
  std::unique_ptr<py::error_already_set> error_;
  std::atomic<bool> stop_{false};
};

py::dict RunSceneFile(const std::string& scene_path, const std::string& out, int threads,
                      bool restart, bool keep_checkpoint, const py::object& progress,
                      const py::object& log) {
  const dem::Scene scene = dem::Scene::Load(scene_path);
  CheckOutputs({{"out", out}, {"the checkpoint (out + .ckpt)", out + ".ckpt"}}, scene.InputFiles());
  dem::RunOptions options;
  options.output_path = out;
  options.threads = threads;
  options.restart = restart;
  options.keep_checkpoint = keep_checkpoint;
  Callbacks callbacks(progress, log);
  options.stop_requested = [&callbacks](int64_t) { return callbacks.stop(); };
  callbacks.Connect<dem::RunProgress>(&options);
  dem::RunSummary summary;
  {
    py::gil_scoped_release release;
    summary = dem::RunScene(scene, options);
  }
  callbacks.Rethrow();
  py::dict result = SummaryDict(summary);
  result["path"] = out;
  return result;
}

py::dict RunProgramme(const std::string& programme_path, const std::string& scale_name,
                      const std::string& out, int jobs, int threads, const py::object& progress,
                      const py::object& log) {
  const std::optional<study::Scale> scale = FromString<study::Scale>(scale_name);
  if (!scale) {
    throw InputError(fmt::format("scale '{}' is not valid: expected {}", scale_name,
                                 AllowedNames<study::Scale>()));
  }
  CheckOutputFolder({"out", out}, {{"the programme", programme_path}});
  const study::Programme programme = study::Programme::Load(programme_path, *scale);
  const study::Parallelism parallelism = study::ChooseParallelism(
      HardwareThreads(), dem::PhysicalMemoryBytes(), programme.At(*scale).count, jobs, threads);
  study::RunnerOptions options;
  options.jobs = parallelism.jobs;
  const study::Plan plan = study::Plan::Make(programme, parallelism.threads, out);
  Callbacks callbacks(progress, log);
  options.stop_requested = [&callbacks] { return callbacks.stop(); };
  callbacks.Connect<study::StudyProgress>(&options);
  study::StudyOutcome outcome;
  std::string tables;
  {
    py::gil_scoped_release release;
    outcome = study::RunStudy(plan, options);
    if (!outcome.interrupted()) tables = analysis::WriteStudyTables(out);
  }
  callbacks.Rethrow();
  std::vector<std::string> id, status, message;
  std::vector<double> wall, steps;
  for (const study::CaseOutcome& c : outcome.cases) {
    id.push_back(c.id);
    status.push_back(ToString(c.status));
    message.push_back(c.message);
    wall.push_back(c.wall_seconds);
    steps.push_back(static_cast<double>(c.particle_steps));
  }
  py::dict result;
  result["directory"] = out;
  result["line"] = outcome.OneLine();
  result["interrupted"] = outcome.interrupted();
  result["jobs"] = parallelism.jobs;
  result["threads"] = parallelism.threads;
  result["tables"] = tables;
  result["wall_s"] = outcome.wall_seconds;
  py::dict units;
  units["wall_s"] = "s";
  result["cases"] = DataFrame({{"case", py::cast(id)},
                               {"status", py::cast(status)},
                               {"message", py::cast(message)},
                               {"wall_s", Array(wall)},
                               {"particle_steps", Array(steps).attr("astype")("int64")}},
                              units);
  return result;
}

}  // namespace

void BindRuns(py::module_& module) {
  module.def("run_scene", &RunSceneFile, py::arg("scene"), py::arg("out") = "run.h5", py::kw_only(),
             py::arg("threads") = 0, py::arg("restart") = false, py::arg("keep_checkpoint") = false,
             py::arg("progress") = py::none(), py::arg("log") = py::none(),
             R"(Runs a scene file (TOML) into the result file `out`, as `granasym dem run`; blocks.

threads: 0 takes the scene's. progress(dict) is called at most every 0.25 s with
stage, stages, stage_name, step, steps_per_second, eta_s, p_kpa, e,
psi_sigma_deg and line; log(str) with the run's report lines. Returns the
summary (termination: completed, failed or interrupted). Bad input raises
granasym.InputError; an exception in a callback, or Ctrl-C, stops the run
(results and checkpoint kept: restart=True continues it) and is raised.)");
  module.def(
      "run_programme", &RunProgramme, py::arg("programme"), py::arg("scale") = "small",
      py::arg("out") = "study", py::kw_only(), py::arg("jobs") = 0, py::arg("threads") = 0,
      py::arg("progress") = py::none(), py::arg("log") = py::none(),
      R"(Runs a programme (TOML) at a scale (tiny, small, medium, paper) into the study folder
`out`, as `granasym study run`, and writes the study's tables; blocks.

jobs, threads: 0 chooses them as the command does. progress(dict) gets total,
done, running, left, failed, cached, particle_steps_per_second, eta_s and line;
log(str) the runner's lines. Returns a dict with the cases (a DataFrame of
case, status, message, wall_s, particle_steps), the outcome's line, the
tables' summary and whether it was interrupted. Running it again computes
only what is missing. Exceptions as for run_scene.)");
}

}  // namespace granasym::python
