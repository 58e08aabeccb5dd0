// Runs a study's plan: cases in dependency order, independent cases in
// parallel, each cached under its key (a second run computes only what is
// missing or changed), interrupted cases resumed from their checkpoints, and
// shards of one study sharing a folder through file locks.
//
// Like the DEM run, the library neither prints nor handles signals: lines
// and progress go to the callbacks of RunnerOptions.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "common/enum_names.h"
#include "study/plan.h"

namespace granasym::study {

enum class CaseStatus { kComputed, kCached, kFailed, kBlocked, kInterrupted };
}  // namespace granasym::study

template <>
struct granasym::EnumNames<granasym::study::CaseStatus> {
  static constexpr EnumEntry<study::CaseStatus> kEntries[] = {
      {study::CaseStatus::kComputed, "computed", "run now, all stages completed"},
      {study::CaseStatus::kCached, "cached", "a result for the same inputs was there"},
      {study::CaseStatus::kFailed, "failed", "the run failed; its results up to the failure kept"},
      {study::CaseStatus::kBlocked, "blocked", "its parent has no state to start from"},
      {study::CaseStatus::kInterrupted, "interrupted", "stopped on request; run again to resume"},
  };
};

namespace granasym::study {

struct StudyProgress {
  int total = 0, done = 0, running = 0, left = 0, failed = 0, cached = 0;
  double particle_steps_per_second = 0;  // measured, all jobs together
  double eta_seconds = -1;               // < 0 when not yet known
  std::string OneLine() const;
};

struct RunnerOptions {
  int jobs = 1;  // cases at once
  int shard_index = 1, shard_count = 1;
  std::function<bool()> stop_requested;  // polled; true interrupts the running cases
  std::function<void(const std::string& line)> log;
  std::function<void(const StudyProgress& progress)> progress;
  double progress_period_s = 0.5;
};

struct CaseOutcome {
  std::string id;
  CaseStatus status = CaseStatus::kBlocked;
  std::string message;
  double wall_seconds = 0;
  int64_t particle_steps = 0;  // computed in this invocation
};

struct StudyOutcome {
  std::vector<CaseOutcome> cases;  // the shard's cases, in plan order
  double wall_seconds = 0;
  int Count(CaseStatus status) const;
  bool interrupted() const { return Count(CaseStatus::kInterrupted) > 0; }
  std::string OneLine() const;
};

// Prepares DIR (refusing a folder that holds something else), generates the
// samples and runs the shard's cases.
StudyOutcome RunStudy(const Plan& plan, const RunnerOptions& options);

}  // namespace granasym::study
