#include "study/study_folder.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <thread>

#include "common/config.h"
#include "common/error.h"
#include "common/hdf5_file.h"
#include "common/results_version.h"
#include "common/text_file.h"
#include "dem/run_record_names.h"
#include "study/case_record.h"

namespace granasym::study {
namespace fs = std::filesystem;

FileLock::FileLock(const std::string& path, const std::function<bool()>& stop_requested) {
  fd_ = ::open(path.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw RuntimeError("cannot open the lock file '" + path + "': " + std::strerror(errno));
  while (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    if (errno != EWOULDBLOCK && errno != EINTR) {
      const std::string reason = std::strerror(errno);
      ::close(fd_);
      fd_ = -1;
      throw RuntimeError("cannot lock '" + path + "': " + reason);
    }
    if (stop_requested && stop_requested()) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  locked_ = true;
}

FileLock::~FileLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the lock
}

std::vector<std::string> CaseFolders(const std::string& directory, bool with_record) {
  std::vector<std::string> folders;
  const fs::path base = fs::path(directory) / "cases";
  if (!fs::exists(base)) return folders;
  for (const auto& replicate : fs::directory_iterator(base)) {
    if (!replicate.is_directory()) continue;
    for (const auto& entry : fs::directory_iterator(replicate.path())) {
      if (entry.is_directory() &&
          (!with_record || fs::exists(entry.path() / CaseRecord::kFileName))) {
        folders.push_back(entry.path().string());
      }
    }
  }
  std::sort(folders.begin(), folders.end());
  return folders;
}

std::optional<DoneRecord> ReadDone(const std::string& directory) {
  const std::string path = directory + "/done.toml";
  if (!fs::exists(path)) return std::nullopt;
  const ConfigTable table = ConfigTable::ParseFile(path);
  DoneRecord done;
  done.key = table.GetString("key");
  done.termination = table.GetEnum<dem::Termination>("termination");
  done.message = table.GetString("message", "");
  done.steps = table.GetInt("steps", 0, Range::NonNegative());
  done.particles = table.GetInt("particles", 0, Range::NonNegative());
  done.wall_seconds = table.GetDouble("wall_seconds", 0.0, Range::NonNegative());
  if (table.Has("cpu_seconds")) {
    done.cpu_seconds = table.GetDouble("cpu_seconds", 0.0, Range::NonNegative());
  }
  done.inputs.scene_sha256 = table.GetString("scene_sha256", "");
  done.inputs.parent_key = table.GetString("parent_key", "");
  done.inputs.results = table.GetString("results", "");
  done.inputs.threads = static_cast<int>(table.GetInt("threads", 0, Range::NonNegative()));
  return done;
}

std::string ResultMismatch(const std::string& result_path, const DoneRecord& done,
                           bool check_data) {
  try {
    const Hdf5File file = Hdf5File::OpenRead(result_path);
    const dem::RunSummary summary = dem::ReadSummary(file);
    if (summary.termination != done.termination) {
      return fmt::format("{} holds a run that ended '{}' ({}), not the '{}' of done.toml",
                         result_path, ToString(summary.termination), summary.message,
                         ToString(done.termination));
    }
    // (Results written by hand, e.g. by tests, may have no provenance.)
    const dem::Provenance provenance =
        file.Exists(dem::record::kProvenance) ? dem::ReadProvenance(file) : dem::Provenance{};
    if (!provenance.case_key.empty()) {
      if (provenance.case_key != done.key) {
        return fmt::format(
            "{} is the result of another case: its provenance's case key is {}, this case's "
            "key is {}",
            result_path, provenance.case_key, done.key);
      }
    } else if (!done.inputs.empty() && file.Exists(dem::record::kProvenance)) {
      // A result written before the case key was recorded.
      if (provenance.scene_sha256 != done.inputs.scene_sha256) {
        return fmt::format(
            "{} is the result of another scene: its provenance's scene hash is {}, done.toml "
            "records {}",
            result_path, provenance.scene_sha256, done.inputs.scene_sha256);
      }
      if (provenance.threads != done.inputs.threads) {
        return fmt::format("{} was computed with {} threads, done.toml records {}", result_path,
                           provenance.threads, done.inputs.threads);
      }
    }
    if (check_data) file.CheckData();
    return "";
  } catch (const InputError& error) {
    return error.what();
  } catch (const RuntimeError& error) {
    // A damaged file can fail a read in ways other than a checksum.
    return std::string(error.what()) + " (the file is damaged)";
  }
}

std::string KeyInputs::Difference(const KeyInputs& now) const {
  if (empty()) return "it was computed by an older version that did not record its key's inputs";
  std::vector<std::string> changes;
  if (results != now.results) {
    changes.push_back("the results key changed (" + results + " → " + now.results + ")");
  }
  if (scene_sha256 != now.scene_sha256) changes.push_back("its scene changed");
  if (parent_key != now.parent_key) {
    changes.push_back("its parent (or sample) has another key");
  }
  if (threads != now.threads) {
    changes.push_back(fmt::format("the thread count changed ({} → {})", threads, now.threads));
  }
  std::string text;
  for (size_t k = 0; k < changes.size(); ++k) text += (k ? "; " : "") + changes[k];
  return text;
}

void WriteDone(const std::string& directory, const DoneRecord& done) {
  std::string inputs;
  if (!done.inputs.empty()) {
    inputs = fmt::format(
        "# the inputs of the key\nscene_sha256 = {}\nparent_key = {}\nresults = {}\n"
        "threads = {}\n",
        TomlQuoted(done.inputs.scene_sha256), TomlQuoted(done.inputs.parent_key),
        TomlQuoted(done.inputs.results), done.inputs.threads);
  }
  WriteTextFileAtomically(
      directory + "/done.toml",
      fmt::format(
          "# written when the case ended; its key names the inputs it was computed for\n"
          "key = {}\ntermination = {}\nmessage = {}\nsteps = {}\nparticles = {}\n"
          "wall_seconds = {:.3f}\n{}{}",
          TomlQuoted(done.key), TomlQuoted(ToString(done.termination)), TomlQuoted(done.message),
          done.steps, done.particles, done.wall_seconds,
          done.cpu_seconds >= 0 ? fmt::format("cpu_seconds = {:.3f}\n", done.cpu_seconds) : "",
          inputs));
}

std::optional<std::string> StudyNclCase(const std::string& directory) {
  const std::string path = directory + "/study.toml";
  if (!fs::exists(path)) return std::nullopt;
  return ConfigTable::ParseFile(path).GetString("ncl", "");
}

void WriteIfChanged(const std::string& path, const std::string& text) {
  if (fs::exists(path) && ReadTextFile(path) == text) return;
  WriteTextFileAtomically(path, text);
}

namespace {

// "r<K>/<case>" of a case folder DIR/cases/r<K>/<case>.
std::string CaseId(const fs::path& folder) {
  return folder.parent_path().filename().string() + "/" + folder.filename().string();
}

}  // namespace

std::map<std::string, int64_t> OwnSteps(const std::string& directory) {
  std::map<std::string, std::pair<int64_t, fs::path>> finished;  // id → done.toml's steps, folder
  for (const std::string& folder : CaseFolders(directory, false)) {
    if (const std::optional<DoneRecord> done = ReadDone(folder)) {
      finished[CaseId(folder)] = {done->steps, folder};
    }
  }
  // The step each (parent, stage) ends at, read once from the parent's result.
  std::map<std::pair<std::string, std::string>, int64_t> fork_step;
  std::map<std::string, int64_t> own;
  for (const auto& [id, done] : finished) {
    const auto& [steps, folder] = done;
    int64_t start = 0;
    if (fs::exists(folder / CaseRecord::kFileName)) {
      const CaseRecord record = CaseRecord::Read(folder.string());
      const std::string& parent = record.parent;
      const std::string& stage = record.parent_stage;
      const auto parent_done = finished.find(parent);
      if (parent_done != finished.end()) {
        const auto [at, added] = fork_step.try_emplace({parent, stage}, parent_done->second.first);
        const fs::path result = parent_done->second.second / "result.h5";
        if (added && !stage.empty() && fs::exists(result)) {
          const Hdf5File file = Hdf5File::OpenRead(result.string());
          if (const std::optional<int64_t> step = dem::StageEndStep(file, stage))
            at->second = *step;
        }
        start = at->second;
      }
    }
    own[id] = steps - start;
  }
  return own;
}

std::string DescribeStudy(const std::string& directory) {
  if (!fs::exists(directory + "/study.toml")) {
    throw InputError(directory + ": not a study folder (no study.toml)");
  }
  std::string text = ReadTextFile(directory + "/study.toml");
  std::map<std::string, int> counts;
  std::vector<std::string> lines;
  // The programme's cases (plan.tsv): folders of cases it no longer names
  // are counted, not listed; its cases without a folder are listed as not run.
  std::vector<fs::path> folders;
  const std::optional<std::vector<CaseRecord>> planned = ReadPlannedCases(directory);
  std::set<std::string> planned_ids;
  if (planned) {
    for (const CaseRecord& c : *planned) planned_ids.insert(c.id);
  }
  int outside = 0;
  for (const std::string& folder : CaseFolders(directory, false)) {
    if (planned && !planned_ids.count(CaseId(folder))) {
      ++outside;
      continue;
    }
    planned_ids.erase(CaseId(folder));
    folders.emplace_back(folder);
  }
  if (planned) {
    for (const std::string& id : planned_ids) folders.push_back(fs::path(directory) / "cases" / id);
    std::sort(folders.begin(), folders.end());
  }
  const std::map<std::string, int64_t> own_steps = OwnSteps(directory);
  double particle_steps = 0, wall_seconds = 0;
  int64_t case_steps = 0;
  // Cases whose results key is not this build's: `study run` computes them again.
  const std::string results_key = ResultsKey();
  std::map<std::string, int> other_results;
  for (const fs::path& folder : folders) {
    const std::string id = CaseId(folder);
    std::string status;
    if (const std::optional<DoneRecord> done = ReadDone(folder.string())) {
      status = ToString(done->termination);
      if (done->inputs.results != results_key) ++other_results[done->inputs.results];
      const int64_t own = own_steps.at(id);  // every case with a done.toml
      case_steps += own;
      particle_steps += static_cast<double>(own) * static_cast<double>(done->particles);
      wall_seconds += done->wall_seconds;
      lines.push_back(fmt::format("{:<40} {:<11} {:>9} steps  {}", id, status, own, done->message));
    } else if (fs::exists(folder / "result.h5.ckpt")) {
      status = "checkpointed";
      lines.push_back(fmt::format("{:<40} {}", id, "checkpointed (resumes on the next run)"));
    } else {
      status = "not_run";
      lines.push_back(fmt::format("{:<40} {}", id, "not run"));
    }
    ++counts[status];
  }
  for (const std::string& line : lines) text += line + "\n";
  std::string summary =
      fmt::format("{} cases{}:", folders.size(), planned ? " in the programme" : " (case folders)");
  for (const auto& [status, count] : counts) summary += fmt::format(" {} {}", count, status);
  if (outside > 0) {
    summary += fmt::format(
        "\n{} case folders are not in the programme (plan.tsv): not part of the study; their "
        "cached results stay for a programme that names them again",
        outside);
  }
  summary += fmt::format(
      "\nfinished cases: {} steps of their own, {:.4g} particle-steps, {:.1f} s of case wall "
      "time ({:.3g} particle-steps/s per case)",
      case_steps, particle_steps, wall_seconds,
      wall_seconds > 0 ? particle_steps / wall_seconds : 0.0);
  for (const auto& [key, count] : other_results) {
    summary += fmt::format(
        "\n{} finished cases were computed {}; this build's results key is '{}': `study run` "
        "computes them again (a commit that changes no result keeps the key: "
        "common/results_version.h)",
        count,
        key.empty() ? "by an older version, whose keys held the program version"
                    : "with the results key '" + key + "'",
        results_key);
  }
  return text + summary + "\n";
}

std::string ShardMarkerPath(const std::string& directory, int index, int count) {
  return fmt::format("{}/shards/{}-of-{}.toml", directory, index, count);
}

std::vector<std::string> UnfinishedShards(const std::vector<std::string>& directories, int count) {
  std::vector<std::string> unfinished;
  for (int k = 1; k <= count; ++k) {
    std::string why = "never ended (no shards/" + std::to_string(k) + "-of-" +
                      std::to_string(count) + ".toml: not run, killed, or stopped by an error)";
    for (const std::string& directory : directories) {
      const std::string path = ShardMarkerPath(directory, k, count);
      if (!fs::exists(path)) continue;
      const ConfigTable marker = ConfigTable::ParseFile(path);
      const std::string study = directory + "/study.toml";
      const std::string hash =
          fs::exists(study) ? ConfigTable::ParseFile(study).GetString("programme_sha256", "") : "";
      if (marker.GetString("programme_sha256", "") != hash) {
        why = "its marker " + path + " is of another programme (a run before it was edited)";
        continue;
      }
      const std::string status = marker.GetString("status");
      if (status == "complete") {
        why.clear();
        break;
      }
      why = fmt::format("ended {} ({} failed, {} blocked, {} interrupted cases; {})", status,
                        marker.GetInt("failed", 0, Range::NonNegative()),
                        marker.GetInt("blocked", 0, Range::NonNegative()),
                        marker.GetInt("interrupted", 0, Range::NonNegative()), path);
    }
    if (!why.empty()) unfinished.push_back(fmt::format("shard {}/{}: {}", k, count, why));
  }
  return unfinished;
}

MergeSummary MergeStudies(const std::vector<std::string>& inputs, const std::string& output) {
  if (inputs.empty()) throw InputError("study merge: give at least one study folder");
  std::string record;
  for (const std::string& input : inputs) {
    if (!fs::exists(input + "/study.toml")) {
      throw InputError(input + ": not a study folder (no study.toml)");
    }
    const std::string text = ReadTextFile(input + "/study.toml");
    if (record.empty()) record = text;
    if (text != record) {
      // Name the first key that differs, with both values.
      std::string what = "the files differ";
      const ConfigTable first = ConfigTable::ParseString(record, inputs.front() + "/study.toml");
      const ConfigTable other = ConfigTable::ParseString(text, input + "/study.toml");
      auto value = [](const ConfigTable& table, const std::string& key) -> std::string {
        if (!table.Has(key)) return "";
        if (key == "threads" || key == "replicates" || key == "count") {
          return std::to_string(table.GetInt(key, 0, Range::Any()));
        }
        return table.GetString(key, "");
      };
      for (const char* key : {"programme", "programme_file", "scale", "threads", "replicates",
                              "count", "ncl", "programme_sha256", "program_version"}) {
        const std::string a = value(first, key), b = value(other, key);
        if (a != b) {
          what = fmt::format("{} is '{}' there and '{}' here", key, a, b);
          break;
        }
      }
      throw InputError(input + "/study.toml differs from " + inputs.front() + "/study.toml (" +
                       what +
                       "): only shards of one study (programme, scale, threads, version) can be "
                       "merged");
    }
  }
  std::optional<std::string> plan_text;  // the first input's plan.tsv
  for (const std::string& input : inputs) {
    const std::string plan_path = input + "/" + kPlanFileName;
    const std::optional<std::string> text =
        fs::exists(plan_path) ? std::optional<std::string>(ReadTextFile(plan_path)) : std::nullopt;
    if (input == inputs.front()) {
      plan_text = text;
    } else if (text != plan_text) {
      auto cases = [](const std::optional<std::string>& t) {
        return t ? std::to_string(std::count(t->begin(), t->end(), '\n') - 2) + " cases"
                 : std::string("none");
      };
      throw InputError(fmt::format(
          "{}/{} differs from {}/{} ({} there, {} here): only shards of one programme can be "
          "merged",
          input, kPlanFileName, inputs.front(), kPlanFileName, cases(plan_text), cases(text)));
    }
  }
  const bool in_place = inputs.size() == 1 && fs::exists(output) &&
                        fs::equivalent(fs::path(inputs.front()), fs::path(output));
  if (!in_place) {
    for (const std::string& input : inputs) {
      if (fs::exists(output) && fs::equivalent(input, output)) {
        throw InputError("study merge: --out " + output +
                         " is one of several inputs; merge into a new folder");
      }
    }
    if (fs::exists(output) && !fs::is_empty(output)) {
      throw InputError("study merge: --out " + output + " is not empty; give a new folder");
    }
    fs::create_directories(output);
    WriteTextFileAtomically(output + "/study.toml", record);
    if (plan_text) WriteTextFileAtomically(output + "/" + kPlanFileName, *plan_text);
  }
  std::map<std::string, std::string> keys;  // case id → key
  for (const std::string& input : inputs) {
    for (const char* top : {"samples", "cases", "models"}) {
      const fs::path base = fs::path(input) / top;
      if (!fs::exists(base)) continue;
      for (const auto& replicate : fs::directory_iterator(base)) {
        if (!replicate.is_directory()) continue;
        std::vector<fs::path> folders;
        if (std::string(top) != "cases") {
          folders.push_back(replicate.path());
        } else {
          for (const auto& entry : fs::directory_iterator(replicate.path())) {
            if (entry.is_directory()) folders.push_back(entry.path());
          }
        }
        for (const fs::path& folder : folders) {
          const std::string id = fs::relative(folder, input).string();
          std::string key;
          if (std::string(top) != "samples") {
            const std::optional<DoneRecord> done = ReadDone(folder.string());
            if (!done) continue;  // not finished in this input
            key = done->key;
          } else {
            if (!fs::exists(folder / "key")) continue;
            key = ReadTextFile((folder / "key").string());
          }
          const auto [it, inserted] = keys.emplace(id, key);
          if (!inserted) {
            if (it->second != key) {
              throw InputError("study merge: " + id + " has different inputs in two folders (" +
                               input + " and an earlier one)");
            }
            continue;
          }
          if (in_place) continue;
          const fs::path target = fs::path(output) / id;
          fs::create_directories(target);
          for (const auto& file : fs::directory_iterator(folder)) {
            const std::string name = file.path().filename().string();
            if (!file.is_regular_file() || name == ".lock" || name == "running.toml" ||
                (name.size() > 5 && name.substr(name.size() - 5) == ".ckpt")) {
              continue;
            }
            std::error_code error;
            fs::create_hard_link(file.path(), target / name, error);
            if (error) fs::copy_file(file.path(), target / name);
          }
        }
      }
    }
  }
  // Every case of the study (the plan's, or every folder's without one):
  // finished, or why not.
  MergeSummary summary;
  const std::vector<CaseRecord> records = ReadCaseRecords(output);
  if (plan_text) summary.planned = static_cast<int>(records.size());
  for (const CaseRecord& c : records) {
    const CaseDone done = c.Done();
    if (done.finished) {
      ++summary.finished;
      continue;
    }
    std::string why;
    if (!fs::exists(c.directory)) {
      why = "no case folder in any input (was its shard run?)";
    } else if (!done.mismatch.empty()) {
      why = done.mismatch;
    } else if (done.current) {
      why = "done.toml but no result.h5";
    } else if (done.done) {
      why = "computed for other inputs, not run for the current ones";
    } else if (fs::exists(c.directory + "/result.h5.ckpt")) {
      why = "interrupted (a checkpoint in its input folder: run its shard again)";
    } else {
      why = "not run";
    }
    summary.missing.push_back(c.id + ": " + why);
  }
  return summary;
}

std::string MergeSummary::Text(size_t listed) const {
  std::string text = planned >= 0
                         ? fmt::format("{} of the plan's {} cases finished", finished, planned)
                         : fmt::format("{} finished cases", finished);
  if (missing.empty()) return text + "\n";
  text += fmt::format("; {} without a result (rows with status no_result in the state table):",
                      missing.size());
  for (size_t k = 0; k < missing.size() && k < listed; ++k) text += "\n  " + missing[k];
  if (missing.size() > listed) text += fmt::format("\n  … and {} more", missing.size() - listed);
  return text + "\n";
}

}  // namespace granasym::study
