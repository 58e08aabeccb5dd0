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
      "particle_steps_per_second = {:.6g}\ngeneration_seconds = {:.6g}\nmeasured = {}\n",
      TomlQuoted(rate.cpu_model), rate.threads, rate.spheres, TomlQuoted(rate.results_key),
      rate.particle_steps_per_second, rate.generation_seconds, TomlQuoted(rate.measured_at));
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

MeasuredRate MeasureRate(const Programme& programme, int64_t spheres, int threads) {
  GRANASYM_CHECK(spheres >= 2 && threads >= 1) << spheres << " spheres, " << threads << " threads";
  const int64_t steps =
      std::clamp(static_cast<int64_t>(kCalibrationParticleSteps / static_cast<double>(spheres)),
                 kCalibrationMinSteps, kCalibrationMaxSteps);
  std::string gsd;
  if (!programme.sample.gsd_path.empty()) {
    gsd = "gsd = " + TomlQuoted(fs::absolute(programme.sample.gsd_path).string()) + "\n";
  }
  // The default scene (studies/scenes/ncl_default.toml: default material,
  // Δt = 1.2e-7 s, isotropic compression at 167 1/s) at this sample size, to
  // 100 kPa: the grains jam, as in the states a study's cases run through
  // (a loose sample's steps cost less: few contacts). Its rate: a second run
  // from that state, isochoric shear at 167 1/s for the measured steps.
  const std::string prepare = fmt::format(
      "[sample.generate]\ncount = {}\ncell_size_mm = {:.17g}\nseed = {}\nmax_attempts = {}\n{}"
      "[numerics]\ntime_step_s = {:g}\nthreads = {}\n"
      "[output]\ninterval_strain = 1.0\n"
      "[[stage]]\nname = \"compress\"\npsi_epsilon_deg = 0.0\nstretching_rate = 167.0\n"
      "[stage.stop]\nmean_stress_kpa = 100.0\nstrain_norm = 0.6\n",
      spheres, programme.sample.CellSizeMm(spheres), programme.sample.seed,
      programme.sample.max_attempts, gsd, kCalibrationTimeStep, threads);
  std::string folder_template = (fs::temp_directory_path() / "granasym-rate-XXXXXX").string();
  if (!mkdtemp(folder_template.data())) {
    throw FileError("cannot create a temporary folder for the rate measurement in " +
                    fs::temp_directory_path().string());
  }
  const std::string folder = folder_template;
  const std::string measure = fmt::format(
      "[sample]\nstate = {}\n[numerics]\ntime_step_s = {:g}\nthreads = {}\n"
      "[output]\ninterval_strain = 1.0\n"
      "[[stage]]\nname = \"rate\"\npsi_epsilon_deg = 90.0\nstretching_rate = 167.0\n"
      "[stage.stop]\nsteps = {}\n",
      TomlQuoted(folder + "/prepare.h5"), kCalibrationTimeStep, threads, steps);
  dem::RunSummary prepared, summary;
  double cpu_seconds = 0;  // of the measured run, all threads
  try {
    dem::RunOptions options;
    options.threads = threads;
    options.output_path = folder + "/prepare.h5";
    prepared = dem::RunScene(
        dem::Scene::Parse(prepare, "the rate measurement's preparation", folder), options);
    if (prepared.termination == dem::Termination::kCompleted) {
      options.output_path = folder + "/rate.h5";
      const std::clock_t start = std::clock();
      summary = dem::RunScene(dem::Scene::Parse(measure, "the rate measurement", folder), options);
      cpu_seconds = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
    } else {
      summary = prepared;
    }
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(folder, ignored);
    throw;
  }
  std::error_code ignored;
  fs::remove_all(folder, ignored);
  if (summary.termination != dem::Termination::kCompleted ||
      !(summary.particle_steps_per_second > 0)) {
    throw RuntimeError("the rate measurement (" + std::to_string(spheres) +
                       " spheres) did not complete: " + summary.message);
  }
  MeasuredRate rate;
  rate.cpu_model = HostCpuModel();
  rate.threads = threads;
  rate.spheres = spheres;
  rate.results_key = ResultsKey();
  // The machine's rate when it runs the study alone: the processor time of
  // the measured run per thread, not its wall time, which other programs
  // on a shared machine stretch (the wall-clock rate where that is higher).
  const double particle_steps = summary.particle_steps_per_second * summary.loop_seconds;
  const double busy = cpu_seconds / threads;
  rate.particle_steps_per_second = summary.particle_steps_per_second;
  if (busy > 0) {
    rate.particle_steps_per_second =
        std::max(rate.particle_steps_per_second, particle_steps / busy);
  }
  rate.generation_seconds = std::max(0.0, prepared.wall_seconds - prepared.loop_seconds);
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
double Schedule(const Plan& plan, const std::vector<CaseCost>& costs,
                const std::vector<int>& selected, int jobs) {
  const std::set<int> in(selected.begin(), selected.end());
  std::map<int, double> below;
  for (auto it = selected.rbegin(); it != selected.rend(); ++it) {
    double total = costs[static_cast<size_t>(*it)].seconds;
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
      running.emplace(now + costs[static_cast<size_t>(k)].seconds, k);
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

PlanCost EstimateCost(const Plan& plan, const MeasuredRate& rate, int jobs, int shards) {
  GRANASYM_CHECK(rate.particle_steps_per_second > 0 && jobs >= 1 && shards >= 0)
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
    c.seconds = c.particle_steps / rate.particle_steps_per_second;
    chain[k] = c.seconds + (planned.parent < 0 ? 0.0 : chain[static_cast<size_t>(planned.parent)]);
    cost.critical_seconds = std::max(cost.critical_seconds, chain[k]);
    cost.particle_steps += c.particle_steps;
    cost.case_seconds += c.seconds;
    cost.cases.push_back(c);
  }
  cost.generation_seconds = rate.generation_seconds * static_cast<double>(plan.samples.size());
  std::vector<int> all(plan.cases.size());
  for (size_t k = 0; k < all.size(); ++k) all[k] = static_cast<int>(k);
  cost.wall_seconds = cost.generation_seconds + Schedule(plan, cost.cases, all, jobs);
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
    shard.seconds = rate.generation_seconds * static_cast<double>(replicates.size()) +
                    Schedule(plan, cost.cases, selected, jobs);
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
