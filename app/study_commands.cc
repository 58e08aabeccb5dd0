#include "app/study_commands.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <mutex>
#include <string>
#include <vector>

#include "analysis/study_tables.h"
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
#include "study/cost.h"
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

// The state table and the analyses that belong with it (analysis/study_tables.h).
void WriteTables(const std::string& directory) {
  std::printf("%s", analysis::WriteStudyTables(directory).c_str());
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

  // granasym study plan
  CLI::App* plan_command = study->add_subcommand(
      "plan",
      "dry run: the cases, their depth and estimated particle-steps, the wall time on this "
      "machine at a measured rate, peak memory, jobs x threads and Slurm time limits");
  static std::string plan_programme;
  static study::Scale plan_scale = study::Scale::kSmall;
  static int plan_jobs = 0, plan_threads = 0, plan_shards = 0;
  static bool plan_stages = false, plan_tsv = false;
  plan_command
      ->add_option("programme", plan_programme,
                   "programme file (TOML), e.g. studies/programmes/paper.toml")
      ->required()
      ->check(CLI::ExistingFile);
  AddEnumOption(plan_command, "--scale", &plan_scale, "sample size");
  plan_command
      ->add_option("--jobs", plan_jobs,
                   "cases at once (default: as `study run` chooses; per array task with --shards)")
      ->check(CLI::Range(1, 1024));
  plan_command
      ->add_option("--threads", plan_threads,
                   "OpenMP threads per case (default: as `study run` chooses)")
      ->check(CLI::Range(1, 1024));
  plan_command
      ->add_option("--shards", plan_shards,
                   "Slurm array tasks (`study run --shard K/N`): each shard's time and a time "
                   "limit per task")
      ->check(CLI::Range(1, 100000));
  plan_command->add_flag("--stages", plan_stages,
                         "each stage's estimated strain norm, steps and the stop that ends it");
  plan_command->add_flag(
      "--tsv", plan_tsv,
      "print only the cases as tab-separated values with a header (id, depth, "
      "time step, steps, loose (still) and stress-summing steps, particle-steps, "
      "seconds, at_most, and where at_most the low end of the range: earliest_steps, "
      "earliest_seconds) for scripts");
  plan_command->callback([] {
    const study::Programme programme = study::Programme::Load(plan_programme, plan_scale);
    const int64_t spheres = programme.At(plan_scale).count;
    const study::Parallelism parallelism = study::ChooseParallelism(
        HardwareThreads(), dem::PhysicalMemoryBytes(), spheres, plan_jobs, plan_threads);
    const study::Plan plan = study::Plan::Make(programme, parallelism.threads, "study");
    if (plan_shards > static_cast<int>(plan.cases.size())) {
      throw InputError(
          fmt::format("--shards {}: the programme has {} cases at scale {}: use at "
                      "most {} shards",
                      plan_shards, plan.cases.size(), ToString(plan_scale), plan.cases.size()));
    }
    if (!plan_tsv) {
      std::printf(
          "study plan of '%s' at scale %s: %zu cases (%zu replicates of %zu) of %lld "
          "spheres, %zu model element tests\n",
          programme.name.c_str(), ToString(plan_scale), plan.cases.size(), plan.samples.size(),
          programme.cases.size(), static_cast<long long>(spheres), plan.model_cases.size());
      std::fflush(stdout);
    }
    const study::MeasuredRate rate = study::RateFor(programme, spheres, parallelism.threads);
    if (plan_tsv) {
      const study::PlanCost cost = study::EstimateCost(plan, rate, parallelism.jobs, 0);
      std::printf(
          "case\tdepth\ttime_step_s\tsteps\tloose_steps\tstill_steps\tstress_steps\t"
          "particle_steps\tseconds\tat_most\tearliest_steps\tearliest_seconds\n");
      for (const study::CaseCost& c : cost.cases) {
        const study::PlannedCase& planned = plan.cases[static_cast<size_t>(c.index)];
        std::printf("%s\t%d\t%.6g\t%.6g\t%.6g\t%.6g\t%.6g\t%.6g\t%.6g\t%d\t%.6g\t%.6g\n",
                    planned.id.c_str(), c.depth, planned.time_step, c.steps,
                    planned.estimated_loose_steps, planned.estimated_still_steps,
                    planned.estimated_stress_steps, c.particle_steps, c.seconds, c.at_most ? 1 : 0,
                    c.earliest_steps, c.earliest_seconds);
      }
      return;
    }
    const std::string cache = study::RateCachePath();
    std::printf(
        "rate: %.3g particle-steps/s per case at %lld spheres on %d thread(s) (jammed; loose "
        "%.3g at 167 1/s, %.3g at 1 1/s; stress on every step %.3g), sample generation %.2g s "
        "(%s %s on %s)\n",
        rate.particle_steps_per_second, static_cast<long long>(spheres), rate.threads,
        rate.loose_particle_steps_per_second, rate.still_particle_steps_per_second,
        rate.controlled_particle_steps_per_second, rate.generation_seconds,
        rate.cached ? "cached, measured" : "measured now", rate.measured_at.c_str(),
        rate.cpu_model.c_str());
    if (!rate.cached) {
      std::printf("  (%s)\n", cache.empty() ? "not cached: neither XDG_CACHE_HOME nor HOME is set"
                                            : ("cached in " + cache).c_str());
    }
    const study::PlanCost cost = study::EstimateCost(plan, rate, parallelism.jobs, plan_shards);
    size_t width = 4;
    for (const study::PlannedCase& c : plan.cases) width = std::max(width, c.id.size());
    std::printf("\n%-*s  %5s  %10s  %10s  %14s  %10s\n", static_cast<int>(width), "case", "depth",
                "time step", "steps", "particle-steps", "time");
    for (const study::CaseCost& c : cost.cases) {
      const study::PlannedCase& planned = plan.cases[static_cast<size_t>(c.index)];
      std::printf("%-*s  %5d  %10.3g  %10.3g  %14.3g  %10s%s\n", static_cast<int>(width),
                  planned.id.c_str(), c.depth, planned.time_step, c.steps, c.particle_steps,
                  study::DurationText(c.seconds).c_str(),
                  c.at_most
                      ? ("  at most (from " + study::DurationText(c.earliest_seconds) + ")").c_str()
                      : "");
      if (plan_stages) {
        for (size_t k = 0; k < planned.stage_steps.size(); ++k) {
          const study::StageSteps& stage = planned.stage_steps[k];
          std::printf("    stage %zu: strain %.3g, %.3g steps%s%s: %s\n", k + 1, stage.strain,
                      stage.steps,
                      stage.loose_steps > 0
                          ? fmt::format(" ({:.3g} before it jams)", stage.loose_steps).c_str()
                          : "",
                      stage.at_most ? fmt::format(" (from strain {:.3g}, {:.3g} steps)",
                                                  stage.earliest.strain, stage.earliest.steps)
                                          .c_str()
                                    : "",
                      stage.reason.c_str());
        }
      }
    }
    std::printf(
        "\ntotal: %zu cases, depth up to %d, %.3g steps, %.3g particle-steps, %s of case "
        "time; %zu sample(s) generated first, %s\n",
        cost.cases.size(), cost.max_depth(),
        [&] {
          double steps = 0;
          for (const study::CaseCost& c : cost.cases) steps += c.steps;
          return steps;
        }(),
        cost.particle_steps, study::DurationText(cost.case_seconds).c_str(), plan.samples.size(),
        study::DurationText(cost.generation_seconds).c_str());
    if (cost.at_most_cases > 0) {
      std::printf(
          "  %d case(s) marked 'at most' may end earlier (a stage that stops when the sample "
          "liquefies, where the model cannot tell: it is bounded by the stage's strain cap, "
          "under the inertial rule at its floor of p): %s of the case time is such a bound, %s "
          "the rest; if each such stage liquefies as early as the model allows (its gas window "
          "after an unloading to the gas floor, or at once on an isochoric path under the "
          "inertial rule), %s in all\n",
          cost.at_most_cases, study::DurationText(cost.at_most_seconds).c_str(),
          study::DurationText(cost.case_seconds - cost.at_most_seconds).c_str(),
          study::DurationText(cost.earliest_case_seconds).c_str());
    }
    // A time, or the range from its low end where the two read differently.
    auto range = [](double low, double high) {
      const std::string from = study::DurationText(low), to = study::DurationText(high);
      return from == to ? to : "between " + from + " and " + to;
    };
    std::printf(
        "wall time on this machine: %s with %d jobs x %d thread(s) (the longest chain of "
        "cases: %s)\n",
        range(cost.earliest_wall_seconds, cost.wall_seconds).c_str(), parallelism.jobs,
        parallelism.threads, study::DurationText(cost.critical_seconds).c_str());
    std::printf("peak memory: ~%.3g GB (%d case(s) at once of %lld spheres, %.0f B/sphere)\n",
                cost.peak_memory_bytes / 1e9, parallelism.jobs, static_cast<long long>(spheres),
                study::kCaseBytesPerSphere);
    std::printf("jobs x threads: %d x %d (%s)\n", parallelism.jobs, parallelism.threads,
                parallelism.reason.c_str());
    if (plan_shards > 0) {
      std::printf(
          "\nSlurm, %d shards (array tasks) of %d job(s) x %d thread(s), at this machine's "
          "rate:\n",
          plan_shards, parallelism.jobs, parallelism.threads);
      for (const study::ShardCost& shard : cost.shards) {
        std::printf("  shard %d/%d: %d cases, %s\n", shard.index, plan_shards, shard.cases,
                    range(shard.earliest_seconds, shard.seconds).c_str());
      }
      std::printf("time limit per array task: --time=%s (%.1f x the longest shard at its bound)\n",
                  study::SlurmTime(cost.shard_time_limit_seconds).c_str(), study::kTimeLimitMargin);
    } else {
      std::printf("(Slurm: --shards N gives each array task's time and a time limit)\n");
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
