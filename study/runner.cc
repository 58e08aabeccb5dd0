#include "study/runner.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <thread>
#include <vector>

#include "common/config.h"
#include "common/error.h"
#include "common/provenance.h"
#include "common/stopwatch.h"
#include "common/text_file.h"
#include "dem/grain_size_distribution.h"
#include "dem/scene.h"
#include "dem/simulation.h"
#include "study/case_queue.h"
#include "study/case_record.h"
#include "study/study_folder.h"

#ifdef GRANASYM_STUDY_HAS_MODELS
#include "constitutive/model_config.h"
#endif

namespace granasym::study {
namespace fs = std::filesystem;
namespace {

CaseRecord RecordOf(const Plan& plan, const PlannedCase& c) {
  CaseRecord record;
  record.id = c.id;
  record.name = c.spec.name;
  record.replicate = c.replicate;
  record.key = c.key;
  record.parent = c.parent >= 0 ? plan.cases[static_cast<size_t>(c.parent)].id : "";
  record.parent_stage = c.spec.parent_stage;
  record.run = c.spec.run;
  record.figures = c.spec.figures;
  record.programme = plan.programme.name;
  record.scale = ToString(plan.scale);
  record.threads = plan.threads;
  record.program_version = plan.program_version;
  record.variables = c.spec.variables;
  return record;
}

void PrepareDirectory(const Plan& plan, const RunnerOptions& options) {
  const fs::path dir(plan.directory);
  const std::string record = plan.directory + "/study.toml";
  if (fs::exists(dir) && !fs::is_directory(dir)) {
    throw InputError("--out " + plan.directory + ": exists and is not a folder");
  }
  fs::create_directories(dir);
  // Shards of one study start at the same time: one of them writes study.toml.
  const FileLock lock(plan.directory + "/.lock", {});
  if (fs::exists(record)) {
    const ConfigTable table = ConfigTable::ParseFile(record);
    const std::string programme = table.GetString("programme", "");
    const std::string scale = table.GetString("scale", "");
    if (programme != plan.programme.name || scale != ToString(plan.scale)) {
      throw InputError("--out " + plan.directory + ": holds the study '" + programme +
                       "' at scale " + scale + ", not '" + plan.programme.name + "' at " +
                       ToString(plan.scale) + ": give another output folder");
    }
    // The same name, another programme: an edited programme, run again
    // (its unchanged cases stay cached), or shards of two programmes.
    const std::string hash = table.GetString("programme_sha256", "");
    if (!hash.empty() && hash != plan.programme_sha256) {
      if (options.shard_count > 1) {
        throw InputError(fmt::format(
            "--out {}: holds the study '{}' of another programme (programme_sha256 {} there, {} "
            "in {}): shards of one study run one programme. Give another output folder, or, "
            "when the programme was edited on purpose, run it once without --shard to make it "
            "this folder's programme (unchanged cases stay cached)",
            plan.directory, programme, hash, plan.programme_sha256, plan.programme.origin));
      }
      if (options.log) {
        options.log(fmt::format(
            "the programme '{}' changed since this folder's last run (programme_sha256 {} → {}): "
            "cases whose inputs did not change stay cached",
            programme, hash, plan.programme_sha256));
      }
    }
  } else {
    for (const auto& entry : fs::directory_iterator(dir)) {
      if (entry.path().filename() == ".lock") continue;
      throw InputError("--out " + plan.directory +
                       ": is not empty and holds no study (no study.toml): give a new or empty "
                       "folder, so that nothing in it is overwritten");
    }
  }
  fs::create_directories(dir / "cases");
  fs::create_directories(dir / "samples");
  WriteIfChanged(record, StudyRecordText(plan));
  // The programme's cases: a case folder of another programme stays (its
  // cache) but is not part of the study.
  std::vector<CaseRecord> planned;
  planned.reserve(plan.cases.size());
  for (const PlannedCase& c : plan.cases) planned.push_back(RecordOf(plan, c));
  WriteIfChanged(plan.directory + "/" + kPlanFileName, PlanFileText(planned));
}

void GenerateSample(const PlannedSample& sample, const std::function<bool()>& stop,
                    const std::function<void(const std::string&)>& log) {
  fs::create_directories(sample.directory);
  FileLock lock(sample.directory + "/.lock", stop);
  if (!lock.locked()) return;
  const std::string key_path = sample.directory + "/key";
  if (fs::exists(key_path) && fs::exists(sample.packing_path()) &&
      ReadTextFile(key_path) == sample.key + "\n") {
    return;
  }
  const dem::GrainSizeDistribution gsd = sample.gsd_path.empty()
                                             ? dem::GrainSizeDistribution::Default()
                                             : dem::GrainSizeDistribution::ReadCsv(sample.gsd_path);
  dem::GenerationReport report;
  const dem::Packing packing = dem::GeneratePacking(gsd, sample.options, &report);
  packing.WriteText(sample.packing_path());
  WriteTextFileAtomically(sample.packing_sha256_path(),
                          Sha256Hex(ReadTextFile(sample.packing_path())) + "\n");
  WriteTextFileAtomically(sample.directory + "/generation.txt", report.Table());
  WriteTextFileAtomically(key_path, sample.key + "\n");
  if (log) {
    log(fmt::format("sample r{}: {} spheres generated, porosity {:.4f}", sample.replicate,
                    report.count, report.porosity));
  }
}

// The key the sample's cases are keyed on when its packing.txt is not the
// one generated for its key (an edited file): nullopt when it is. A sample
// generated before the packing's hash was recorded has it recorded now.
std::optional<std::string> EditedSampleKey(const PlannedSample& sample,
                                           const std::function<void(const std::string&)>& log) {
  FileLock lock(sample.directory + "/.lock", {});
  const std::string now = Sha256Hex(ReadTextFile(sample.packing_path()));
  if (!fs::exists(sample.packing_sha256_path())) {
    WriteTextFileAtomically(sample.packing_sha256_path(), now + "\n");
    return std::nullopt;
  }
  const std::string generated = ReadTextFile(sample.packing_sha256_path());
  if (generated == now + "\n") return std::nullopt;
  if (log) {
    log(fmt::format(
        "sample r{}: {} is not the packing generated for it (SHA-256 {}, generated {}): its "
        "cases are keyed on its content",
        sample.replicate, sample.packing_path(), now, generated.substr(0, generated.find('\n'))));
  }
  return PackingSampleKey(sample.key, now);
}

// An element test of a constitutive model, cached like a DEM case.
CaseOutcome RunModelCase(const PlannedModelCase& m,
                         const std::function<void(const std::string&)>& log) {
  CaseOutcome outcome;
  outcome.id = m.id;
  fs::create_directories(m.directory);
  FileLock lock(m.directory + "/.lock", {});
  if (const std::optional<DoneRecord> done = ReadDone(m.directory);
      done && done->key == m.key && fs::exists(m.directory + "/result.h5")) {
    outcome.status = done->termination == dem::Termination::kCompleted ? CaseStatus::kCached
                                                                       : CaseStatus::kFailed;
    outcome.message = done->message;
    return outcome;
  }
#ifdef GRANASYM_STUDY_HAS_MODELS
  const Stopwatch clock;
  const std::string input = m.directory + "/test.toml";
  WriteIfChanged(input, m.spec.text);
  const ConfigTable root = ConfigTable::ParseString(m.spec.text, input);
  const ElementTestResult result =
      RunElementTestInput(root, input, m.directory + "/result.h5", m.directory + "/result.csv");
  outcome.wall_seconds = clock.Seconds();
  outcome.message = result.summary.Report();
  const bool success = result.summary.success();
  outcome.status = success ? CaseStatus::kComputed : CaseStatus::kFailed;
  WriteDone(m.directory, {m.key,
                          {},
                          success ? dem::Termination::kCompleted : dem::Termination::kFailed,
                          outcome.message,
                          0,
                          0,
                          outcome.wall_seconds});
  if (log) log(m.id + ": " + ToString(outcome.status) + " (" + outcome.message + ")");
#else
  throw InputError(m.id +
                   ": this build has no constitutive models (configure with "
                   "GRANASYM_BUILD_MODELS=ON) and cannot run the programme's [[model_run]]");
#endif
  return outcome;
}

class Scheduler {
 public:
  Scheduler(const Plan& plan, const RunnerOptions& options, const std::vector<int>& selected)
      : plan_(plan),
        options_(options),
        selected_(selected),
        queue_(plan, selected),
        state_(plan.cases.size(), State::kWaiting),
        outcomes_(plan.cases.size()) {
    for (int k : selected_) remaining_work_ += queue_.work(k);
  }

  StudyOutcome Run() {
    const Stopwatch clock;
    const int jobs = std::max(1, std::min<int>(options_.jobs, static_cast<int>(selected_.size())));
    std::vector<std::thread> workers;
    for (int j = 0; j < jobs; ++j) workers.emplace_back([this] { Work(); });
    // The progress reporter runs here; it also watches for a stop request,
    // so that waiting cases are given up within a poll whatever the plan's size.
    const double period = std::min(options_.progress_period_s, 0.2);
    double last_report = -1e30;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      while (finished_ < selected_.size()) {
        cv_done_.wait_for(lock, std::chrono::duration<double>(period));
        if (StopRequested()) {
          InterruptWaitingLocked();
          cv_ready_.notify_all();
        }
        if (options_.progress && clock.Seconds() - last_report >= options_.progress_period_s) {
          last_report = clock.Seconds();
          const StudyProgress progress = ProgressLocked(clock.Seconds());
          lock.unlock();
          options_.progress(progress);
          lock.lock();
        }
      }
    }
    cv_ready_.notify_all();
    for (std::thread& worker : workers) worker.join();
    if (error_) {
      try {
        std::rethrow_exception(error_);
      } catch (const InputError& error) {
        throw InputError("case " + error_case_ + ": " + error.what());
      } catch (const RuntimeError& error) {
        throw RuntimeError("case " + error_case_ + ": " + error.what());
      }
    }
    StudyOutcome outcome;
    for (int k : selected_) outcome.cases.push_back(outcomes_[static_cast<size_t>(k)]);
    outcome.wall_seconds = clock.Seconds();
    return outcome;
  }

 private:
  enum class State { kWaiting, kRunning, kFinished };

  // A stop request, or an error in another case: the running cases
  // checkpoint and no new case starts.
  bool StopRequested() const {
    return aborted_.load() || (options_.stop_requested && options_.stop_requested());
  }

  void Work() {
    for (;;) {
      int k = -1;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        cv_ready_.wait(lock, [this] { return !queue_.empty() || finished_ == selected_.size(); });
        if (queue_.empty()) return;
        if (StopRequested()) {
          InterruptWaitingLocked();
          lock.unlock();
          cv_ready_.notify_all();
          cv_done_.notify_all();
          continue;
        }
        k = queue_.Pop();
        state_[static_cast<size_t>(k)] = State::kRunning;
        ++running_;
      }
      CaseOutcome outcome;
      try {
        outcome = StopRequested() ? NotStarted(k) : Execute(k);
      } catch (...) {
        // An error that is not a result of the case (bad input, a full
        // disk, a violated invariant): the study stops, and RunStudy
        // rethrows it once every worker has ended.
        std::lock_guard<std::mutex> lock(mutex_);
        if (!error_) {
          error_ = std::current_exception();
          error_case_ = plan_.cases[static_cast<size_t>(k)].id;
        }
        aborted_ = true;
        outcome.id = plan_.cases[static_cast<size_t>(k)].id;
        outcome.status = CaseStatus::kInterrupted;
        outcome.message = "stopped by an error";
      }
      {
        std::lock_guard<std::mutex> lock(mutex_);
        --running_;
        Finish(k, outcome);
      }
      cv_ready_.notify_all();
      cv_done_.notify_all();
    }
  }

  void FinishOneLocked(int k, const CaseOutcome& outcome) {
    const size_t i = static_cast<size_t>(k);
    outcomes_[i] = outcome;
    state_[i] = State::kFinished;
    ++finished_;
    remaining_work_ -= queue_.work(k);
    running_progress_.erase(k);
    if (outcome.status == CaseStatus::kFailed || outcome.status == CaseStatus::kBlocked) ++failed_;
    if (outcome.status == CaseStatus::kCached) ++cached_;
  }

  CaseOutcome NotStarted(int k) const {
    return {plan_.cases[static_cast<size_t>(k)].id, CaseStatus::kInterrupted,
            "not started: the study was interrupted", 0, 0};
  }

  // Every case that has not started is interrupted, at once (a stop request).
  void InterruptWaitingLocked() {
    for (int k : queue_.TakeAll()) FinishOneLocked(k, NotStarted(k));
    for (int k : selected_) {
      if (state_[static_cast<size_t>(k)] == State::kWaiting) FinishOneLocked(k, NotStarted(k));
    }
  }

  void Finish(int k, const CaseOutcome& outcome) {
    done_particle_steps_ += outcome.particle_steps;
    FinishOneLocked(k, outcome);
    if (outcome.status == CaseStatus::kInterrupted) {
      // Its children cannot start: they are interrupted too.
      for (int c : queue_.Descendants(k)) {
        if (state_[static_cast<size_t>(c)] == State::kWaiting) FinishOneLocked(c, NotStarted(c));
      }
      return;
    }
    queue_.Release(k);
  }

  StudyProgress ProgressLocked(double elapsed) const {
    StudyProgress p;
    p.total = static_cast<int>(selected_.size());
    p.done = static_cast<int>(finished_);
    p.running = running_;
    p.failed = failed_;
    p.cached = cached_;
    double remaining = remaining_work_, running_done = 0;
    for (const auto& [k, progressed] : running_progress_) {
      if (state_[static_cast<size_t>(k)] != State::kRunning) continue;
      running_done += progressed;
      const double work = queue_.work(k);
      remaining -= work - std::max(0.1 * work, work - progressed);
    }
    p.left = p.total - p.done - p.running;
    const double computed = static_cast<double>(done_particle_steps_) + running_done;
    if (elapsed > 1 && computed > 0) {
      p.particle_steps_per_second = computed / elapsed;
      p.eta_seconds = std::max(0.0, remaining) / p.particle_steps_per_second;
    }
    return p;
  }

  CaseOutcome Execute(int k);

  const Plan& plan_;
  const RunnerOptions& options_;
  const std::vector<int> selected_;
  std::mutex mutex_;
  std::condition_variable cv_ready_, cv_done_;
  CaseQueue queue_;
  std::vector<State> state_;
  std::vector<CaseOutcome> outcomes_;
  std::map<int, double> running_progress_;  // the running cases' particle-steps so far
  double remaining_work_ = 0;               // estimated particle-steps of unfinished cases
  int64_t done_particle_steps_ = 0;
  size_t finished_ = 0;
  int running_ = 0, failed_ = 0, cached_ = 0;
  std::atomic<bool> aborted_{false};
  std::exception_ptr error_;
  std::string error_case_;
};

CaseOutcome Scheduler::Execute(int k) {
  const PlannedCase& c = plan_.cases[static_cast<size_t>(k)];
  CaseOutcome outcome;
  outcome.id = c.id;
  const Stopwatch clock;
  const double cpu0 = ThreadCpuSeconds();
  const std::function<bool()> stop = [this] { return StopRequested(); };
  fs::create_directories(c.directory);
  FileLock lock(c.directory + "/.lock", stop);
  if (!lock.locked()) {
    outcome.status = CaseStatus::kInterrupted;
    outcome.message = "not started: the study was interrupted while waiting for the case's lock";
    return outcome;
  }
  const std::optional<DoneRecord> previous = ReadDone(c.directory);
  if (previous && previous->key != c.key && options_.log) {
    options_.log(c.id + ": computed again: " + previous->inputs.Difference(c.inputs));
  }
  if (const std::optional<DoneRecord>& done = previous;
      done && done->key == c.key && fs::exists(c.result_path())) {
    const std::string mismatch = ResultMismatch(c.result_path(), *done, true);
    if (mismatch.empty()) {
      outcome.status = done->termination == dem::Termination::kCompleted ? CaseStatus::kCached
                                                                         : CaseStatus::kFailed;
      outcome.message = done->message;
      return outcome;
    }
    // Not the result done.toml records: the case runs again.
    if (options_.log) options_.log(c.id + ": " + mismatch + "; computing it again");
    fs::remove(c.directory + "/done.toml");
  }
  // A parent computed by another shard is read from the shared folder.
  if (c.parent >= 0) {
    const PlannedCase& parent = plan_.cases[static_cast<size_t>(c.parent)];
    const std::optional<DoneRecord> done = ReadDone(parent.directory);
    if (!done || done->key != parent.key) {
      outcome.status = CaseStatus::kBlocked;
      outcome.message = "its parent " + parent.id + " has no result for the current inputs";
      return outcome;
    }
  }
  const std::string running_path = c.directory + "/running.toml";
  const bool resume = fs::exists(running_path) && fs::exists(c.result_path() + ".ckpt") &&
                      ReadTextFile(running_path) == "key = " + TomlQuoted(c.key) + "\n";
  if (!resume) {
    for (const char* name : {"/result.h5", "/result.h5.ckpt", "/done.toml"}) {
      fs::remove(c.directory + name);
    }
  }
  WriteIfChanged(c.directory + "/scene.toml", c.scene_text);
  RecordOf(plan_, c).Write(c.directory);
  WriteTextFileAtomically(running_path, "key = " + TomlQuoted(c.key) + "\n");

  const dem::Scene scene =
      dem::Scene::Parse(c.scene_text, c.directory + "/scene.toml", c.directory);
  dem::RunOptions run;
  run.output_path = c.result_path();
  run.threads = plan_.threads;
  run.restart = resume;
  run.case_key = c.key;
  run.stop_requested = [this](int64_t) { return StopRequested(); };
  // The run's own report goes to the case's run.log (appended across
  // resumes); the study's log gets one line when a case starts and ends.
  std::ofstream run_log(c.directory + "/run.log", std::ios::app);
  run.log = [&run_log](const std::string& line) {
    run_log << line << (!line.empty() && line.back() == '\n' ? "" : "\n");
    run_log.flush();
  };
  int64_t first_step = -1;
  run.progress = [this, k, &first_step, &c](const dem::RunProgress& progress) {
    if (first_step < 0) first_step = progress.step;
    std::lock_guard<std::mutex> lock(mutex_);
    running_progress_[k] =
        static_cast<double>(progress.step - first_step) * static_cast<double>(c.particles);
  };
  run.progress_period_s = 0.5;
  if (options_.log)
    options_.log(c.id + ": " + (resume ? "resuming from its checkpoint" : "started"));
  dem::RunSummary summary;
  try {
    summary = dem::RunScene(scene, run);
  } catch (const InputError& error) {
    if (c.parent < 0) throw;
    // The parent ended before the state this case starts from.
    outcome.status = CaseStatus::kBlocked;
    outcome.message = error.what();
    fs::remove(running_path);
    if (options_.log) options_.log(c.id + ": blocked: " + outcome.message);
    return outcome;
  }
  outcome.wall_seconds = clock.Seconds();
  outcome.particle_steps =
      static_cast<int64_t>(summary.particle_steps_per_second * summary.loop_seconds);
  outcome.message = summary.message;
  if (summary.termination == dem::Termination::kInterrupted) {
    outcome.status = CaseStatus::kInterrupted;
    return outcome;
  }
  // On one thread the case's processor time is the thread's (the DEM runs
  // on it); with more, the workers' time is not counted: not recorded.
  WriteDone(c.directory, {c.key, c.inputs, summary.termination, summary.message, summary.steps,
                          summary.particles, outcome.wall_seconds,
                          plan_.threads == 1 ? ThreadCpuSeconds() - cpu0 : -1.0});
  fs::remove(running_path);
  outcome.status = summary.termination == dem::Termination::kCompleted ? CaseStatus::kComputed
                                                                       : CaseStatus::kFailed;
  if (options_.log) {
    options_.log(fmt::format("{}: {} in {:.1f} s ({}){}", c.id, ToString(outcome.status),
                             outcome.wall_seconds, summary.message,
                             summary.validity.empty() ? "" : "; " + summary.validity));
  }
  return outcome;
}

std::string EtaText(double seconds) {
  if (seconds < 0) return "?";
  const int64_t s = static_cast<int64_t>(seconds + 0.5);
  if (s >= 3600) return fmt::format("{}h{:02d}m", s / 3600, static_cast<int>(s % 3600 / 60));
  if (s >= 60) return fmt::format("{}m{:02d}s", s / 60, static_cast<int>(s % 60));
  return fmt::format("{}s", s);
}

}  // namespace

std::string StudyProgress::OneLine() const {
  return fmt::format(
      "cases {}/{} done ({} cached, {} failed), {} running, {} left | {:.3g} "
      "particle-steps/s | ETA {}",
      done, total, cached, failed, running, left, particle_steps_per_second, EtaText(eta_seconds));
}

int StudyOutcome::Count(CaseStatus status) const {
  return static_cast<int>(std::count_if(
      cases.begin(), cases.end(), [status](const CaseOutcome& c) { return c.status == status; }));
}

std::string StudyOutcome::OneLine() const {
  std::string line = fmt::format("{} cases in {:.1f} s:", cases.size(), wall_seconds);
  for (CaseStatus status : EnumValues<CaseStatus>()) {
    line += fmt::format(" {} {}", Count(status), ToString(status));
  }
  return line;
}

StudyOutcome RunStudy(const Plan& plan, const RunnerOptions& options) {
  if (options.jobs < 1) throw InputError("--jobs must be at least 1");
  if (options.shard_count < 1 || options.shard_index < 1 ||
      options.shard_index > options.shard_count) {
    throw InputError(fmt::format("--shard {}/{}: expected K/N with 1 <= K <= N",
                                 options.shard_index, options.shard_count));
  }
  PrepareDirectory(plan, options);
  const bool sharded = options.shard_count > 1;
  const std::string marker =
      ShardMarkerPath(plan.directory, options.shard_index, options.shard_count);
  if (sharded) {
    fs::create_directories(plan.directory + "/shards");
    fs::remove(marker);  // an earlier run's: this one has not ended
  }
  const std::vector<int> selected = plan.Shard(options.shard_index, options.shard_count);
  std::set<int> replicates;
  for (int k : selected) replicates.insert(plan.cases[static_cast<size_t>(k)].replicate);
  std::map<int, std::string> edited;  // replicate → the key of its edited sample
  for (const PlannedSample& sample : plan.samples) {
    if (replicates.count(sample.replicate)) {
      GenerateSample(sample, options.stop_requested, options.log);
      if (options.stop_requested && options.stop_requested()) break;
      if (const std::optional<std::string> key = EditedSampleKey(sample, options.log)) {
        edited[sample.replicate] = *key;
      }
    }
  }
  std::optional<Plan> keyed;
  if (!edited.empty()) {
    keyed = plan;
    keyed->KeyOnSamples(edited);
  }
  const Plan& run_plan = keyed ? *keyed : plan;
  // Model runs are quick and belong to the first shard.
  std::vector<CaseOutcome> models;
  if (options.shard_index == 1) {
    for (const PlannedModelCase& m : plan.model_cases) {
      if (options.stop_requested && options.stop_requested()) break;
      models.push_back(RunModelCase(m, options.log));
    }
  }
  Scheduler scheduler(run_plan, options, selected);
  StudyOutcome outcome = scheduler.Run();
  outcome.cases.insert(outcome.cases.end(), models.begin(), models.end());
  if (sharded) {
    const int failed = outcome.Count(CaseStatus::kFailed),
              blocked = outcome.Count(CaseStatus::kBlocked),
              interrupted = outcome.Count(CaseStatus::kInterrupted);
    const char* status = interrupted > 0        ? "interrupted"
                         : failed + blocked > 0 ? "failed"
                                                : "complete";
    WriteTextFileAtomically(
        marker,
        fmt::format("# written by granasym study run --shard {}/{} when it ended\n"
                    "status = {}\nprogramme_sha256 = {}\ncases = {}\ncomputed = {}\n"
                    "cached = {}\nfailed = {}\nblocked = {}\ninterrupted = {}\n"
                    "wall_seconds = {:.1f}\n",
                    options.shard_index, options.shard_count, TomlQuoted(status),
                    TomlQuoted(plan.programme_sha256), outcome.cases.size(),
                    outcome.Count(CaseStatus::kComputed), outcome.Count(CaseStatus::kCached),
                    failed, blocked, interrupted, outcome.wall_seconds));
  }
  return outcome;
}

}  // namespace granasym::study
