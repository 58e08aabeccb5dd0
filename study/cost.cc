#include "study/cost.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <map>
#include <set>

#include "common/config.h"
#include "common/error.h"
#include "common/provenance.h"
#include "common/text_file.h"
#include "dem/scene.h"
#include "dem/simulation.h"
#include "study/parallelism.h"

namespace granasym::study {
namespace fs = std::filesystem;
namespace {

// About 2·10⁷ particle-steps: a few seconds on one core, long enough that
// the neighbour list's rebuilds and the clock's resolution do not matter.
constexpr double kCalibrationParticleSteps = 2e7;
constexpr int64_t kCalibrationMinSteps = 500;
constexpr int64_t kCalibrationMaxSteps = 20000;
constexpr double kCalibrationTimeStep = 1.2e-7;  // s, the paper's

std::string UtcNow() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

std::string EntryText(const MeasuredRate& rate) {
  return fmt::format(
      "[[rate]]\ncpu = {}\nthreads = {}\nspheres = {}\nresults_key = {}\n"
      "particle_steps_per_second = {:.6g}\nloose_particle_steps_per_second = {:.6g}\n"
      "still_particle_steps_per_second = {:.6g}\n"
      "controlled_particle_steps_per_second = {:.6g}\ngeneration_seconds = {:.6g}\n"
      "measured = {}\n",
      TomlQuoted(rate.cpu_model), rate.threads, rate.spheres, TomlQuoted(rate.results_key),
      rate.particle_steps_per_second, rate.loose_particle_steps_per_second,
      rate.still_particle_steps_per_second, rate.controlled_particle_steps_per_second,
      rate.generation_seconds, TomlQuoted(rate.measured_at));
}

std::vector<MeasuredRate> ReadCache(const std::string& path) {
  std::vector<MeasuredRate> rates;
  if (path.empty() || !fs::exists(path)) return rates;
  const ConfigTable root = ConfigTable::ParseFile(path);
  for (const ConfigTable& entry : root.GetTableArray("rate")) {
    MeasuredRate rate;
    rate.cpu_model = entry.GetString("cpu");
    rate.threads = static_cast<int>(entry.GetInt("threads", Range::Closed(1, 1024)));
    rate.spheres = entry.GetInt("spheres", Range::Closed(2, 2e9));
    rate.results_key = entry.GetString("results_key");
    rate.particle_steps_per_second =
        entry.GetDouble("particle_steps_per_second", Range::Positive());
    rate.generation_seconds = entry.GetDouble("generation_seconds", Range::NonNegative());
    rate.measured_at = entry.GetString("measured");
    rate.cached = true;
    // An entry of an older granasym measured fewer rates (one, of a loose
    // packing, which jammed cases run two to three times slower than): it
    // is measured again and replaced.
    // (Has marks each key as known: every one is asked for.)
    const bool loose = entry.Has("loose_particle_steps_per_second");
    const bool still = entry.Has("still_particle_steps_per_second");
    const bool controlled = entry.Has("controlled_particle_steps_per_second");
    if (!loose || !still || !controlled) continue;
    rate.loose_particle_steps_per_second =
        entry.GetDouble("loose_particle_steps_per_second", Range::Positive());
    rate.still_particle_steps_per_second =
        entry.GetDouble("still_particle_steps_per_second", Range::Positive());
    rate.controlled_particle_steps_per_second =
        entry.GetDouble("controlled_particle_steps_per_second", Range::Positive());
    rates.push_back(rate);
  }
  root.CheckNoUnknownKeys();
  return rates;
}

bool SameKey(const MeasuredRate& rate, const std::string& cpu_model, int threads, int64_t spheres,
             const std::string& results_key) {
  return rate.cpu_model == cpu_model && rate.threads == threads && rate.spheres == spheres &&
         rate.results_key == results_key;
}

}  // namespace

std::string RateCachePath() {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (xdg && *xdg) return (fs::path(xdg) / "granasym" / "rates.toml").string();
  const char* home = std::getenv("HOME");
  if (home && *home) return (fs::path(home) / ".cache" / "granasym" / "rates.toml").string();
  return "";
}

std::optional<MeasuredRate> ReadCachedRate(const std::string& cache_path,
                                           const std::string& cpu_model, int threads,
                                           int64_t spheres, const std::string& results_key) {
  for (const MeasuredRate& rate : ReadCache(cache_path)) {
    if (SameKey(rate, cpu_model, threads, spheres, results_key)) return rate;
  }
  return std::nullopt;
}

void StoreRate(const std::string& cache_path, const MeasuredRate& rate) {
  GRANASYM_CHECK(!cache_path.empty()) << "no cache path";
  std::string text =
      "# granasym study plan: DEM rates measured on this machine (delete the file to measure "
      "again)\n";
  for (const MeasuredRate& old : ReadCache(cache_path)) {
    if (!SameKey(old, rate.cpu_model, rate.threads, rate.spheres, rate.results_key)) {
      text += "\n" + EntryText(old);
    }
  }
  text += "\n" + EntryText(rate);
  const fs::path parent = fs::path(cache_path).parent_path();
  std::error_code error;
  if (!parent.empty()) fs::create_directories(parent, error);
  if (error) {
    throw FileError("cannot create the rate cache's folder '" + parent.string() +
                    "': " + error.message());
  }
  WriteTextFileAtomically(cache_path, text);
}

namespace {

// One timed DEM run: its particle-steps per second of processor time per
// thread (the wall-clock rate where that is higher), and its summary.
struct TimedRun {
  dem::RunSummary summary;
  double rate = 0;
};

TimedRun RunTimed(const std::string& scene_text, const std::string& what, const std::string& folder,
                  const std::string& output, int threads) {
  dem::RunOptions options;
  options.threads = threads;
  options.output_path = folder + "/" + output;
  const dem::Scene scene = dem::Scene::Parse(scene_text, what, folder);
  const std::clock_t start = std::clock();
  TimedRun run;
  run.summary = dem::RunScene(scene, options);
  const double cpu_seconds = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
  if (run.summary.termination != dem::Termination::kCompleted ||
      !(run.summary.particle_steps_per_second > 0)) {
    throw RuntimeError(what + " did not complete: " + run.summary.message);
  }
  // The machine's rate when it runs the study alone: the processor time per
  // thread, not the wall time, which other programs on a shared machine
  // stretch (the wall-clock rate where that is higher).
  const double particle_steps = run.summary.particle_steps_per_second * run.summary.loop_seconds;
  const double busy = cpu_seconds / threads;
  run.rate = run.summary.particle_steps_per_second;
  if (busy > 0) run.rate = std::max(run.rate, particle_steps / busy);
  return run;
}

}  // namespace

MeasuredRate MeasureRate(const Programme& programme, int64_t spheres, int threads) {
  GRANASYM_CHECK(spheres >= 2 && threads >= 1) << spheres << " spheres, " << threads << " threads";
  const int64_t steps =
      std::clamp(static_cast<int64_t>(kCalibrationParticleSteps / static_cast<double>(spheres)),
                 kCalibrationMinSteps, kCalibrationMaxSteps);
  std::string gsd;
  if (!programme.sample.gsd_path.empty()) {
    gsd = "gsd = " + TomlQuoted(fs::absolute(programme.sample.gsd_path).string()) + "\n";
  }
  const std::string numerics =
      fmt::format("[numerics]\ntime_step_s = {:g}\nthreads = {}\n[output]\ninterval_strain = 1.0\n",
                  kCalibrationTimeStep, threads);
  // The default scene (studies/scenes/ncl_default.toml: default material,
  // Δt = 1.2e-7 s, isotropic compression at 167 1/s) at this sample size, to
  // 100 kPa: the loose rate (the generated sample's steps until it jams:
  // few neighbours, few contacts). At 167 1/s the grains reach 100 kPa
  // dynamically, with few contacts; a rest at 100 kPa lets them form the
  // jammed network the cases' stages run in.
  const std::string compress = fmt::format(
      "[sample.generate]\ncount = {}\ncell_size_mm = {:.17g}\nseed = {}\nmax_attempts = {}\n{}"
      "{}[[stage]]\nname = \"compress\"\npsi_epsilon_deg = 0.0\nstretching_rate = 167.0\n"
      "[stage.stop]\nmean_stress_kpa = 100.0\nstrain_norm = 0.6\n",
      spheres, programme.sample.CellSizeMm(spheres), programme.sample.seed,
      programme.sample.max_attempts, gsd, numerics);
  // The same sample at 1 1/s: grains that barely move and do not collide
  // (the loose steps of a quasi-static stage, e.g. under the inertial rule
  // at its floor of p).
  const std::string still = fmt::format(
      "[sample.generate]\ncount = {}\ncell_size_mm = {:.17g}\nseed = {}\nmax_attempts = {}\n{}"
      "{}[[stage]]\nname = \"still\"\npsi_epsilon_deg = 0.0\nstretching_rate = 1.0\n"
      "[stage.stop]\nsteps = {}\n",
      spheres, programme.sample.CellSizeMm(spheres), programme.sample.seed,
      programme.sample.max_attempts, gsd, numerics, steps);
  std::string folder_template = (fs::temp_directory_path() / "granasym-rate-XXXXXX").string();
  if (!mkdtemp(folder_template.data())) {
    throw FileError("cannot create a temporary folder for the rate measurement in " +
                    fs::temp_directory_path().string());
  }
  const std::string folder = folder_template;
  auto from = [&](const std::string& state) {
    return "[sample]\nstate = " + TomlQuoted(folder + "/" + state) + "\n" + numerics;
  };
  const std::string rest = from("compress.h5") +
                           "[[stage]]\nname = \"rest\"\ntype = \"rest\"\nmean_stress_kpa = "
                           "100.0\n[stage.stop]\nsteps = 5000\n";
  const std::string shear = from("rest.h5") + fmt::format(
                                                  "[[stage]]\nname = \"shear\"\npsi_epsilon_deg "
                                                  "= 90.0\nstretching_rate = 167.0\n"
                                                  "[stage.stop]\nsteps = {}\n",
                                                  steps);
  const std::string triaxial =
      from("rest.h5") + fmt::format(
                            "[[stage]]\nname = \"triaxial\"\ntype = \"triaxial\"\n"
                            "axial_strain_rate = 136.355\nradial_stress_kpa = 100.0\n"
                            "[stage.stop]\nsteps = {}\n",
                            steps);
  TimedRun loose, still_run, jammed, controlled;
  const std::string what = "the rate measurement (" + std::to_string(spheres) + " spheres): ";
  try {
    loose = RunTimed(compress, what + "compression", folder, "compress.h5", threads);
    still_run = RunTimed(still, what + "still compression", folder, "still.h5", threads);
    RunTimed(rest, what + "rest", folder, "rest.h5", threads);
    jammed = RunTimed(shear, what + "isochoric shear", folder, "shear.h5", threads);
    controlled = RunTimed(triaxial, what + "triaxial", folder, "triaxial.h5", threads);
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(folder, ignored);
    throw;
  }
  std::error_code ignored;
  fs::remove_all(folder, ignored);
  MeasuredRate rate;
  rate.cpu_model = HostCpuModel();
  rate.threads = threads;
  rate.spheres = spheres;
  rate.results_key = ResultsKey();
  rate.particle_steps_per_second = jammed.rate;
  rate.loose_particle_steps_per_second = loose.rate;
  rate.still_particle_steps_per_second = still_run.rate;
  rate.controlled_particle_steps_per_second = controlled.rate;
  rate.generation_seconds = std::max(0.0, loose.summary.wall_seconds - loose.summary.loop_seconds);
  rate.measured_at = UtcNow();
  return rate;
}

MeasuredRate RateFor(const Programme& programme, int64_t spheres, int threads,
                     const std::string& results_key) {
  const std::string cache = RateCachePath();
  if (std::optional<MeasuredRate> cached =
          ReadCachedRate(cache, HostCpuModel(), threads, spheres, results_key)) {
    return *cached;
  }
  MeasuredRate rate = MeasureRate(programme, spheres, threads);
  rate.results_key = results_key;
  if (!cache.empty()) StoreRate(cache, rate);
  return rate;
}

int PlanCost::max_depth() const {
  int depth = 0;
  for (const CaseCost& c : cases) depth = std::max(depth, c.depth);
  return depth;
}

namespace {

// The runner's schedule (study/runner.cc, Scheduler) replayed with estimated
// times: `jobs` workers, a case ready when its parent (if selected) is done,
// the ready case with the most work below it first. Returns the makespan.
double Schedule(const Plan& plan, const std::vector<double>& seconds,
                const std::vector<int>& selected, int jobs) {
  const std::set<int> in(selected.begin(), selected.end());
  std::map<int, double> below;
  for (auto it = selected.rbegin(); it != selected.rend(); ++it) {
    double total = seconds[static_cast<size_t>(*it)];
    for (int child : plan.cases[static_cast<size_t>(*it)].children) {
      if (in.count(child)) total += below[child];
    }
    below[*it] = total;
  }
  std::vector<int> ready;
  for (int k : selected) {
    const int parent = plan.cases[static_cast<size_t>(k)].parent;
    if (parent < 0 || !in.count(parent)) ready.push_back(k);
  }
  // (finish time, case) of the running cases.
  std::multimap<double, int> running;
  double now = 0, end = 0;
  size_t done = 0;
  while (done < selected.size()) {
    while (static_cast<int>(running.size()) < jobs && !ready.empty()) {
      auto best = std::max_element(ready.begin(), ready.end(),
                                   [&](int a, int b) { return below[a] < below[b]; });
      const int k = *best;
      ready.erase(best);
      running.emplace(now + seconds[static_cast<size_t>(k)], k);
    }
    GRANASYM_CHECK(!running.empty()) << "no case can run: the plan orders parents first";
    const auto first = running.begin();
    now = first->first;
    const int k = first->second;
    running.erase(first);
    ++done;
    end = std::max(end, now);
    for (int child : plan.cases[static_cast<size_t>(k)].children) {
      if (in.count(child)) ready.push_back(child);
    }
  }
  return end;
}

}  // namespace

double CaseSeconds(const MeasuredRate& rate, double particles, double steps, double loose,
                   double still, double stress) {
  const double jammed = std::max(0.0, steps - loose - stress);
  const double colliding = std::max(0.0, loose - still);
  return particles * (jammed / rate.particle_steps_per_second +
                      colliding / rate.loose_particle_steps_per_second +
                      still / rate.still_particle_steps_per_second +
                      stress / rate.controlled_particle_steps_per_second);
}

PlanCost EstimateCost(const Plan& plan, const MeasuredRate& rate, int jobs, int shards) {
  GRANASYM_CHECK(rate.particle_steps_per_second > 0 && rate.loose_particle_steps_per_second > 0 &&
                 rate.still_particle_steps_per_second > 0 &&
                 rate.controlled_particle_steps_per_second > 0 && jobs >= 1 && shards >= 0)
      << rate.particle_steps_per_second << " particle-steps/s, " << jobs << " jobs, " << shards
      << " shards";
  PlanCost cost;
  cost.jobs = jobs;
  std::vector<double> chain(plan.cases.size(), 0.0);
  for (size_t k = 0; k < plan.cases.size(); ++k) {
    const PlannedCase& planned = plan.cases[k];
    CaseCost c;
    c.index = static_cast<int>(k);
    c.depth = planned.parent < 0 ? 1 : cost.cases[static_cast<size_t>(planned.parent)].depth + 1;
    c.steps = planned.estimated_steps;
    c.particle_steps = c.steps * static_cast<double>(planned.particles);
    c.seconds = CaseSeconds(rate, static_cast<double>(planned.particles), c.steps,
                            planned.estimated_loose_steps, planned.estimated_still_steps,
                            planned.estimated_stress_steps);
    c.at_most = planned.steps_at_most;
    const PlannedCase::Earliest& first = planned.estimated_earliest;
    c.earliest_steps = first.steps;
    c.earliest_seconds = CaseSeconds(rate, static_cast<double>(planned.particles), first.steps,
                                     first.loose_steps, first.still_steps, first.stress_steps);
    cost.earliest_case_seconds += c.earliest_seconds;
    if (c.at_most) {
      cost.at_most_seconds += c.seconds;
      ++cost.at_most_cases;
    }
    chain[k] = c.seconds + (planned.parent < 0 ? 0.0 : chain[static_cast<size_t>(planned.parent)]);
    cost.critical_seconds = std::max(cost.critical_seconds, chain[k]);
    cost.particle_steps += c.particle_steps;
    cost.case_seconds += c.seconds;
    cost.cases.push_back(c);
  }
  cost.generation_seconds = rate.generation_seconds * static_cast<double>(plan.samples.size());
  std::vector<int> all(plan.cases.size());
  std::vector<double> seconds, earliest;
  for (size_t k = 0; k < all.size(); ++k) {
    all[k] = static_cast<int>(k);
    seconds.push_back(cost.cases[k].seconds);
    earliest.push_back(cost.cases[k].earliest_seconds);
  }
  cost.wall_seconds = cost.generation_seconds + Schedule(plan, seconds, all, jobs);
  cost.earliest_wall_seconds = cost.generation_seconds + Schedule(plan, earliest, all, jobs);
  const int64_t spheres = plan.cases.empty() ? 0 : plan.cases.front().particles;
  cost.peak_memory_bytes = kCaseBytesPerSphere * static_cast<double>(spheres) *
                           std::min<double>(jobs, std::max<size_t>(plan.cases.size(), 1));
  double longest = 0;
  for (int s = 1; s <= shards; ++s) {
    ShardCost shard;
    shard.index = s;
    const std::vector<int> selected = plan.Shard(s, shards);
    std::set<int> replicates;
    for (int k : selected) replicates.insert(plan.cases[static_cast<size_t>(k)].replicate);
    shard.cases = static_cast<int>(selected.size());
    const double generation = rate.generation_seconds * static_cast<double>(replicates.size());
    shard.seconds = generation + Schedule(plan, seconds, selected, jobs);
    shard.earliest_seconds = generation + Schedule(plan, earliest, selected, jobs);
    longest = std::max(longest, shard.seconds);
    cost.shards.push_back(shard);
  }
  if (shards > 0) cost.shard_time_limit_seconds = 60 * std::ceil(kTimeLimitMargin * longest / 60);
  return cost;
}

std::string DurationText(double seconds) {
  if (seconds < 99.5) return fmt::format("{:.0f} s", seconds);
  if (seconds < 99.5 * 60) return fmt::format("{:.0f} min", seconds / 60);
  if (seconds < 48 * 3600) return fmt::format("{:.1f} h", seconds / 3600);
  return fmt::format("{:.1f} d", seconds / 86400);
}

std::string SlurmTime(double seconds) {
  const int64_t total = static_cast<int64_t>(std::ceil(seconds));
  return fmt::format("{}-{:02d}:{:02d}:{:02d}", total / 86400, (total / 3600) % 24,
                     (total / 60) % 60, total % 60);
}

}  // namespace granasym::study
