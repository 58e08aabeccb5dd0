// The records of a study folder that the runner, status and merge share:
// the exclusive lock of a case folder, done.toml (what a finished case was
// computed for and how it ended), and the folder-level commands.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "dem/run_record.h"

namespace granasym::study {

// An exclusive flock on a file, waited for while polling the stop request
// (`locked()` is false when the wait ended by a stop request). Locks taken
// by threads of one process exclude each other too (one open file
// description each).
class FileLock {
 public:
  FileLock(const std::string& path, const std::function<bool()>& stop_requested);
  ~FileLock();
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;
  bool locked() const { return locked_; }

 private:
  int fd_ = -1;
  bool locked_ = false;
};

// What DIR/.../done.toml records of a finished case.
// What a case's key is made of (study/plan.h): the SHA-256 of its canonical
// scene, its parent's key (the sample's for a case from the sample), the
// results key of the build (common/results_version.h) and the thread count.
// done.toml records them, so that a case computed again can say why.
struct KeyInputs {
  std::string scene_sha256, parent_key, results;
  int threads = 0;
  bool empty() const { return results.empty(); }
  // "" when `now` is the same; else what changed, in words.
  std::string Difference(const KeyInputs& now) const;
};

struct DoneRecord {
  std::string key;
  KeyInputs inputs;  // empty in a done.toml of an older version
  dem::Termination termination = dem::Termination::kNotRun;
  std::string message;
  int64_t steps = 0;  // engine steps at the end, the parent's included
  int64_t particles = 0;
  double wall_seconds = 0;
  // The case's own processor seconds where it ran on one thread (the
  // thread's CPU time: what a plan estimates, on a shared or paused machine
  // too); < 0 where not measured (threads > 1, an older done.toml).
  double cpu_seconds = -1;
};
std::optional<DoneRecord> ReadDone(const std::string& directory);
void WriteDone(const std::string& directory, const DoneRecord& done);
// "" when the DEM result `result_path` is the run `done` records; else why
// not, in one line: a partial result under the final name (a run
// interrupted after done.toml was written by another), the result of
// another case (its /provenance/case_key is not done.key; a result written
// before case keys were recorded: its scene hash or thread count is not the
// one done.toml records), or a result that cannot be read. `check_data`:
// every dataset's checksum is read too (a flipped bit in the data).
std::string ResultMismatch(const std::string& result_path, const DoneRecord& done,
                           bool check_data = false);

// The case folders DIR/cases/r<K>/<case> (those with a case.toml when
// `with_record`), sorted.
std::vector<std::string> CaseFolders(const std::string& directory, bool with_record = true);

// The engine steps each finished case (one with a done.toml) took itself,
// keyed by its id ("r1/nc100_psi0_I0.1"): its done.toml's steps less the
// step it started from. A case forked from a stage of its parent
// (case.toml's parent_stage) starts at the step of that stage's end state in
// the parent's result.h5, one forked from the parent's end at the parent's
// last step, one from a sample at 0.
std::map<std::string, int64_t> OwnSteps(const std::string& directory);

// The study's NCL case (study.toml's `ncl`, which the runner writes from the
// programme; "" when the programme names none), or nullopt without a
// study.toml.
std::optional<std::string> StudyNclCase(const std::string& directory);

// Writes `text` to `path` (atomically) unless the file holds it already.
void WriteIfChanged(const std::string& path, const std::string& text);

// What a study folder holds: one line per case with its status
// (done with its termination and own steps, checkpointed, or not run), a
// count line and the totals of steps and particle-steps.
std::string DescribeStudy(const std::string& directory);

// DIR/shards/<K>-of-<N>.toml: how shard K of N of a sharded `study run`
// ended (written when it ends; removed when it starts). `study merge
// --shards N` names the shards that never ended or whose cases failed.
std::string ShardMarkerPath(const std::string& directory, int index, int count);
// The shards of N among the folders `directories` that did not end with
// every case finished: "shard K/N: why", one per shard. A marker of another
// programme (programme_sha256 of study.toml) counts as none.
std::vector<std::string> UnfinishedShards(const std::vector<std::string>& directories, int count);

// What a merged folder holds against its plan.
struct MergeSummary {
  int finished = 0;                  // cases of the study with their result
  int planned = -1;                  // the plan's cases (plan.tsv); -1 without one
  std::vector<std::string> missing;  // "r1/case: why" for each case of the study without a result
  // A line for the finished cases and, when some are missing, how many and
  // which (at most `listed` named, then how many more).
  std::string Text(size_t listed = 20) const;
};

// Combines the case folders of `inputs` into `output` (hard links where the
// filesystem allows, copies otherwise); `output` may be the only input.
// Two inputs with different keys for one case are an error, and so are
// inputs of different studies (study.toml) or plans (plan.tsv). Every case
// of the plan is either finished in `output` or named in `missing` with why
// (a shard that never ran leaves its cases without a folder).
MergeSummary MergeStudies(const std::vector<std::string>& inputs, const std::string& output);

}  // namespace granasym::study
