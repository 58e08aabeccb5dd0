#include "app/study_commands.h"

#include <cstdio>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "analysis/findings.h"
#include "analysis/rate_cases.h"
#include "app/enum_option.h"
#include "app/progress.h"
#include "app/signals.h"
#include "app/study_compare_command.h"
#include "app/study_figures_command.h"
#include "app/study_report_command.h"
#include "app/thread_count.h"
#ifdef GRANASYM_HAVE_CALIBRATION
#include "app/study_calibrate_command.h"
#endif
#include "common/error.h"
#include "common/output_path.h"
#include "dem/packing.h"
#include "study/parallelism.h"
#include "study/plan.h"
#include "study/programme.h"
#include "study/runner.h"
#include "study/state_table.h"
#include "study/study_folder.h"

namespace granasym {
namespace {

// "K/N" with 1 <= K <= N.
bool ParseShard(const std::string& text, int* index, int* count) {
  const size_t slash = text.find('/');
  if (slash == std::string::npos) return false;
  try {
    size_t used = 0;
    *index = std::stoi(text.substr(0, slash), &used);
    if (used != slash) return false;
    const std::string rest = text.substr(slash + 1);
    *count = std::stoi(rest, &used);
    if (used != rest.size()) return false;
  } catch (const std::exception&) {
    return false;
  }
  return *count >= 1 && *index >= 1 && *index <= *count;
}

// The state table, then the analyses that belong with it: the paper's claims
// judged from the study (analysis/findings.h), and for a study with rate
// cases the rate study's files (analysis/rate_cases.h, analysis/rate_files.h).
void WriteTables(const std::string& directory) {
  std::printf("%s", study::WriteStateTable(directory).Text().c_str());
  std::printf("%s", analysis::FindingsLine(analysis::WriteStudyFindings(directory)).c_str());
  if (const std::optional<analysis::RateStudy> rate =
          analysis::WriteRateStudy(directory, study::ReadStateTable(directory))) {
    std::printf("%s", rate->Text().c_str());
  }
}

}  // namespace

void RegisterStudyCommands(CLI::App& app) {
  CLI::App* study = app.add_subcommand(
      "study", "programmes of DEM runs: cases forked from shared states, cached, in parallel");
  study->require_subcommand(1);

  // granasym study run
  CLI::App* run = study->add_subcommand("run", "run a programme (TOML) into a study folder");
  static std::string programme_path, out = "study";
  static study::Scale scale = study::Scale::kSmall;
  static int jobs = 0, threads = 0;  // 0: chosen (study/parallelism.h)
  static std::string shard = "1/1";
  static bool quiet = false;
  run->add_option("programme", programme_path,
                  "programme file (TOML), e.g. studies/programmes/paper.toml")
      ->required()
      ->check(CLI::ExistingFile);
  AddEnumOption(run, "--scale", &scale, "sample size");
  run->add_option("--out", out, "study folder (created; a second run reuses its results)");
  run->add_option("--jobs", jobs,
                  "cases run at once (default: one single-thread case per hardware thread, "
                  "as many as the memory holds at the scale's sample size)")
      ->check(CLI::Range(1, 1024));
  run->add_option("--threads", threads,
                  "OpenMP threads per case (default: chosen with --jobs; part of each case's "
                  "key: results are bit-identical for a fixed count)")
      ->check(CLI::Range(1, 1024));
  run->add_option("--shard", shard,
                  "run slice K of N (1-based) into a folder shared by all shards; merge with "
                  "`study merge`");
  run->add_flag("--quiet", quiet, "no progress output");
  run->callback([] {
    study::RunnerOptions options;
    if (!ParseShard(shard, &options.shard_index, &options.shard_count)) {
      throw InputError("--shard " + shard + ": expected K/N with 1 <= K <= N, e.g. 2/4");
    }
    CheckOutputFolder({"--out", out}, {{"the programme", programme_path}});
    if (threads > 0) threads = CapThreads(threads, "--threads");
    const study::Programme programme = study::Programme::Load(programme_path, scale);
    const study::Parallelism parallelism = study::ChooseParallelism(
        HardwareThreads(), dem::PhysicalMemoryBytes(), programme.At(scale).count, jobs, threads);
    jobs = parallelism.jobs;
    threads = parallelism.threads;
    if (jobs * threads > HardwareThreads()) {
      std::fprintf(stderr,
                   "warning: --jobs %d x --threads %d = %d threads on %d hardware threads: cases "
                   "will wait for cores\n",
                   jobs, threads, jobs * threads, HardwareThreads());
    }
    options.jobs = jobs;
    const study::Plan plan = study::Plan::Make(programme, threads, out);
    Progress::Options progress_options;
    progress_options.quiet = quiet;
    progress_options.plain_interval_s = 30;
    Progress progress(progress_options);
    const SignalGuard signals;
    options.stop_requested = [] { return InterruptRequested(); };
    std::mutex print;
    if (!quiet) {
      options.log = [&](const std::string& line) {
        std::lock_guard<std::mutex> lock(print);
        progress.Finish();
        std::fprintf(stderr, "%s\n", line.c_str());
      };
      options.progress = [&](const study::StudyProgress& state) {
        std::lock_guard<std::mutex> lock(print);
        if (progress.Due()) progress.Report(state.OneLine());
      };
    }
    std::printf(
        "study '%s' at scale %s: %zu cases (%zu replicates of %zu), shard %d/%d, "
        "%d jobs x %d threads (%s), into %s\n",
        programme.name.c_str(), ToString(scale), plan.cases.size(), plan.samples.size(),
        programme.cases.size(), options.shard_index, options.shard_count, jobs, threads,
        parallelism.reason.c_str(), out.c_str());
    const study::StudyOutcome outcome = study::RunStudy(plan, options);
    progress.Finish();
    std::printf("%s\n", outcome.OneLine().c_str());
    if (outcome.interrupted()) {
      std::printf("interrupted: run the same command again to resume\n");
      throw CLI::RuntimeError(130);
    }
    if (options.shard_count == 1) {
      WriteTables(out);
    } else {
      std::printf("shard %d/%d done; when all shards are done: granasym study merge %s --out %s\n",
                  options.shard_index, options.shard_count, out.c_str(), out.c_str());
    }
    // Failed and blocked cases are results of the study (the table says
    // why): a whole study exits 0; a shard exits 3, so that its array task
    // shows as failed (the merge job runs after the array in any case and
    // names the shard: study merge --shards N).
    const int unfinished =
        outcome.Count(study::CaseStatus::kFailed) + outcome.Count(study::CaseStatus::kBlocked);
    if (unfinished > 0) {
      std::printf(
          "%d cases failed or were blocked: see the message column of the state table "
          "or `granasym study status %s`\n",
          unfinished, out.c_str());
      if (options.shard_count > 1) throw CLI::RuntimeError(3);
    }
  });

  // granasym study status
  CLI::App* status = study->add_subcommand("status", "what a study folder holds, case by case");
  static std::string status_dir;
  status->add_option("dir", status_dir, "study folder")->required()->check(CLI::ExistingDirectory);
  status->callback([] { std::printf("%s", study::DescribeStudy(status_dir).c_str()); });

  // granasym study merge
  CLI::App* merge = study->add_subcommand(
      "merge", "combine the folders of shards and write the table of asymptotic states");
  static std::vector<std::string> inputs;
  static std::string merge_out;
  merge->add_option("dirs", inputs, "study folders (shards of one study)")
      ->required()
      ->check(CLI::ExistingDirectory);
  merge->add_option("--out", merge_out, "merged study folder (may be the only input)")->required();
  static int merge_shards = 0;
  merge
      ->add_option("--shards", merge_shards,
                   "the study ran as N shards (--shard K/N): name every shard that did not end "
                   "with all its cases finished (DIR/shards/K-of-N.toml)")
      ->check(CLI::Range(1, 1000000));
  merge->callback([] {
    const std::vector<std::string> shards = merge_shards > 0
                                                ? study::UnfinishedShards(inputs, merge_shards)
                                                : std::vector<std::string>{};
    const study::MergeSummary merged = study::MergeStudies(inputs, merge_out);
    std::printf("%s: %s", merge_out.c_str(), merged.Text().c_str());
    WriteTables(merge_out);
    // Shards that did not finish, cases of the study without a result: the
    // table is written (their rows say why), and the status says the study
    // is incomplete.
    for (const std::string& line : shards) std::printf("%s\n", line.c_str());
    if (!merged.missing.empty() || !shards.empty()) {
      std::printf(
          "incomplete: %zu of %d shards did not finish, %zu cases have no result (listed "
          "above)\n",
          shards.size(), merge_shards, merged.missing.size());
      throw CLI::RuntimeError(3);
    }
  });
#ifdef GRANASYM_HAVE_CALIBRATION
  RegisterStudyCalibrateCommand(study);
#endif
  RegisterStudyFiguresCommand(study);
  RegisterStudyReportCommand(study);
  RegisterStudyCompareCommand(study);
}

}  // namespace granasym
