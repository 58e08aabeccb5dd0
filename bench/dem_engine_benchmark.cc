// Cost of one DEM time step per particle on a dense packing (coordination
// number >= 4) with the paper's material: friction, rotations and local
// damping on, ψ_ε = 0° loading at ‖D‖ = 167 1/s, Δt = 1.2e-7 s.
// The argument `law` selects the contact law (material.h): 0 the paper's
// linear law, 1 Hertz–Mindlin (ν = 0.25), 2 linear with rolling resistance
// (μ_r = 0.1), 3 Hertz–Mindlin with rolling resistance; the other material
// values are the paper's. The packing is the same for all (made with the
// linear law), so the laws are compared on the same contacts.
//
// The dense packings are made once and cached as text packings in
// $GRANASYM_BENCH_CACHE (default: the system temporary folder): a generated
// sample of the paper's GSD is compressed frictionless along ψ_ε = 0° to
// 500 kPa and rested there (servo-controlled isotropic stress) until the
// unbalanced force is below 1e-3: a jammed packing with Z ≈ 6.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>

#include "common/state_measures.h"
#include "dem/contact_statistics.h"
#include "dem/engine.h"
#include "dem/packing.h"
#include "dem/scene.h"
#include "dem/simulation.h"

namespace granasym::dem {
namespace {

// E 500 MPa, ν 0.3 (k_s/k_n) or 0.25 (Poisson's ratio), φ 0.5 rad, χ 0.5.
Material BenchmarkMaterial(int law) {
  Material material;
  if (law == 1 || law == 3) material.contact_law = ContactLaw::kHertzMindlin;
  if (law >= 2) material.rolling_friction = 0.1;
  return material;
}

std::string LawName(int law) {
  const Material material = BenchmarkMaterial(law);
  return std::string(ToString(material.contact_law)) +
         (material.has_rolling_resistance() ? "+rolling" : "");
}

std::string CachePath(size_t count) {
  const char* dir = std::getenv("GRANASYM_BENCH_CACHE");
  const std::filesystem::path base = dir ? dir : std::filesystem::temp_directory_path();
  return (base / ("granasym_dense_" + std::to_string(count) + ".txt")).string();
}

const Packing& DensePacking(size_t count) {
  static std::map<size_t, Packing> cache;
  auto found = cache.find(count);
  if (found != cache.end()) return found->second;
  const std::string path = CachePath(count);
  if (!std::filesystem::exists(path)) {
    const std::string scene_text =
        "[sample.generate]\ncount = " + std::to_string(count) +
        "\ncell_size_mm = " + std::to_string(31.0 * std::cbrt(count / 150000.0)) +
        "\n[material]\nfriction_angle_rad = 0.0\n[numerics]\ntime_step_s = 1.2e-7\nthreads = 2\n"
        "[output]\ninterval_strain = 0.05\n"
        "[[stage]]\nname = 'compress'\npsi_epsilon_deg = 0.0\nstretching_rate = 167.0\n"
        "[stage.stop]\nmean_stress_kpa = 500.0\n"
        "[[stage]]\nname = 'rest'\ntype = 'rest'\nmean_stress_kpa = 500.0\n"
        "[stage.stop]\nunbalanced_force = 1e-3\ntime_s = 0.002\n";
    const Scene scene = Scene::Parse(scene_text, "dense packing fixture", "");
    RunOptions options;
    options.output_path = path + ".h5";
    const RunSummary summary = RunScene(scene, options);
    if (summary.termination != Termination::kCompleted) {
      throw std::runtime_error("dense packing fixture failed: " + summary.message);
    }
    const Packing dense = ReadResultPacking(options.output_path, "/final_state");
    dense.WriteText(path);
    std::filesystem::remove(options.output_path);
  }
  return cache[count] = Packing::ReadText(path);
}

void BM_DemStep(benchmark::State& state) {
  const size_t count = static_cast<size_t>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const int law = static_cast<int>(state.range(2));
  const Packing& packing = DensePacking(count);
  Engine::Options options;
  options.threads = threads;
  Engine engine(packing, BenchmarkMaterial(law), options);
  state.SetLabel(LawName(law));
  const AxisymmetricRate rate = AxisymmetricRate::FromAngle(0.0, 167.0);
  engine.SetVelocityGradient({-rate.axial, -rate.radial, -rate.radial});
  for (int step = 0; step < 50; ++step) engine.Step();  // build lists, warm caches
  const int64_t near_builds = engine.near_pairs().builds();
  for (auto _ : state) engine.Step();
  const ContactStatistics contacts = MeasureContacts(engine, nullptr);
  const double particle_steps = static_cast<double>(state.iterations()) * count;
  state.counters["particle_steps_per_s"] =
      benchmark::Counter(particle_steps, benchmark::Counter::kIsRate);
  state.counters["us_per_particle_step"] = benchmark::Counter(
      particle_steps / 1e6, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["coordination"] = contacts.coordination;
  state.counters["mechanical_coordination"] = contacts.mechanical_coordination;
  state.counters["pairs_per_particle"] =
      static_cast<double>(engine.neighbors().pair_count()) / count;
  // The pairs the force pass walks (near_list.h) and how often that list is
  // rebuilt.
  state.counters["near_pairs_per_particle"] =
      static_cast<double>(engine.near_pairs().pair_count()) / count;
  state.counters["steps_per_near_build"] =
      static_cast<double>(state.iterations()) /
      std::max<int64_t>(1, engine.near_pairs().builds() - near_builds);
}

// Every law at 10 000 spheres; the paper's law and Hertz–Mindlin at 150 000.
void Arguments(benchmark::internal::Benchmark* benchmark) {
  for (int threads : {1, 2}) {
    for (int law : {0, 1, 2, 3}) benchmark->Args({10000, threads, law});
  }
  for (int threads : {1, 2}) {
    for (int law : {0, 1}) benchmark->Args({150000, threads, law});
  }
}

BENCHMARK(BM_DemStep)
    ->ArgNames({"N", "threads", "law"})
    ->Apply(Arguments)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

}  // namespace
}  // namespace granasym::dem

BENCHMARK_MAIN();
