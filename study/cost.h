// What a study will cost before it runs (`granasym study plan`): each case's
// particle-steps (its particles times the steps its stages' stop conditions
// imply at the scene's own time step, PlannedCase::estimated_steps from the
// model of study/stage_steps.h), its time at the measured DEM rates, the
// study's wall time with `jobs` cases at once (the runner's order: the
// ready case with the most work below it first), its peak memory, and for a
// Slurm array each shard's time and a time limit per array task. A case
// that may end earlier (liquefaction) counts with its bound ("at most").
//
// The rates are measured, not assumed: short runs of the default material
// on this machine (the generated sample of the programme's GSD at the
// scale's sphere count and cell compressed at 1 1/s, grains that do not
// collide, and at 167 1/s to 100 kPa: the rates of a loose packing; brought to rest there, so that
// the grains form a jammed network; then sheared isochorically at 167 1/s: the rate of a jammed
// packing; and loaded in drained triaxial compression: the rate of a step that sums the stress),
// cached per machine in $XDG_CACHE_HOME/granasym/rates.toml (~/.cache without it), keyed by CPU
// model, threads, sphere count and results key. A jammed step costs two to
// three times a loose one (more neighbours and contacts per sphere).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "study/plan.h"

namespace granasym::study {

// A measured DEM rate: particle-steps per second of one case (its time
// stepping), and the seconds to generate its sample.
struct MeasuredRate {
  std::string cpu_model;
  int threads = 1;
  int64_t spheres = 0;
  std::string results_key;
  double particle_steps_per_second = 0;             // jammed, the stress on output rows only
  double loose_particle_steps_per_second = 0;       // before the generated sample jams, at 167 1/s
  double still_particle_steps_per_second = 0;       // loose, at 1 1/s: grains that do not collide
  double controlled_particle_steps_per_second = 0;  // jammed, the stress on every step
  double generation_seconds = 0;
  std::string measured_at;  // UTC, ISO 8601
  bool cached = false;      // read from the cache, not measured by this call
};

// $XDG_CACHE_HOME/granasym/rates.toml, else $HOME/.cache/granasym/rates.toml;
// "" when neither variable is set (nothing is cached).
std::string RateCachePath();

// The cached rate for this key, if any (InputError naming the file, entry
// and key when the cache is malformed: delete it to measure again).
std::optional<MeasuredRate> ReadCachedRate(const std::string& cache_path,
                                           const std::string& cpu_model, int threads,
                                           int64_t spheres, const std::string& results_key);
// Adds `rate` to the cache (replacing an entry with its key); creates the folder.
void StoreRate(const std::string& cache_path, const MeasuredRate& rate);

// Measures the rates on this machine: the default material with a sample
// of `spheres` (the programme's GSD and cell for that count) compressed to
// 100 kPa (loose), at rest there (untimed, at most 5000 steps), sheared
// isochorically (jammed) and loaded in drained triaxial compression
// (stress on every step), each timed over about 2·10⁷ particle-steps (500
// to 20 000 steps) on `threads` threads, in a temporary folder that is
// removed afterwards (the paper's 150 000 spheres: a few minutes, once per
// machine). The rates are per thread of processor time, so that other
// programs on a shared machine do not lower them: the estimate is for the
// machine running the study alone.
MeasuredRate MeasureRate(const Programme& programme, int64_t spheres, int threads);

// The cached rate, or a measurement that is then cached.
MeasuredRate RateFor(const Programme& programme, int64_t spheres, int threads,
                     const std::string& results_key = ResultsKey());

struct CaseCost {
  int index = 0;  // into Plan::cases
  int depth = 1;  // 1: starts from the sample; a child is one deeper than its parent
  double steps = 0;
  double particle_steps = 0;
  double seconds = 0;
  bool at_most = false;  // a bound: a stage may end earlier (PlannedCase::steps_at_most)
  // If its stages that may liquefy do so as early as the model allows
  // (PlannedCase::estimated_earliest; the same as steps, seconds otherwise).
  double earliest_steps = 0;
  double earliest_seconds = 0;
};

struct ShardCost {
  int index = 1;  // 1-based, as `study run --shard K/N`
  int cases = 0;  // its cases, the ancestors it may compute included
  double seconds = 0;
  double earliest_seconds = 0;  // its cases at CaseCost::earliest_seconds
};

struct PlanCost {
  std::vector<CaseCost> cases;  // in the plan's order
  double particle_steps = 0;    // over all cases
  double case_seconds = 0;      // the cases' times added up
  double at_most_seconds = 0;   // of them, those of cases whose figure is a bound
  int at_most_cases = 0;
  // The low end of the range: every stage that may liquefy does so as early
  // as the model allows (CaseCost::earliest_seconds).
  double earliest_case_seconds = 0;
  double earliest_wall_seconds = 0;
  double generation_seconds = 0;
  int jobs = 1;
  double wall_seconds = 0;       // with `jobs` cases at once, samples first
  double critical_seconds = 0;   // the longest chain of parent and children
  double peak_memory_bytes = 0;  // `jobs` cases at once
  std::vector<ShardCost> shards;
  double shard_time_limit_seconds = 0;  // kTimeLimitMargin × the longest shard, whole minutes
  int max_depth() const;
};

// A Slurm time limit is the longest shard's estimate times this (the
// estimate's aim is ±30 %; a task past its limit is killed and rerun).
inline constexpr double kTimeLimitMargin = 1.5;

// The seconds of `steps` steps of `particles` spheres of which `loose` come
// before the sample jams (`still` of them too slow for its grains to
// collide) and `stress` sum the stress on every step.
double CaseSeconds(const MeasuredRate& rate, double particles, double steps, double loose,
                   double still, double stress);

// The cost of `plan` at `rate` with `jobs` cases at once; with `shards` > 0
// also each shard's (Plan::Shard, run with `jobs` cases at once per task).
PlanCost EstimateCost(const Plan& plan, const MeasuredRate& rate, int jobs, int shards);

// Seconds as "45 s", "12 min", "3.4 h"; a Slurm time as "D-HH:MM:SS".
std::string DurationText(double seconds);
std::string SlurmTime(double seconds);

}  // namespace granasym::study
