// Cost of one DEM time step per particle on a dense packing (coordination
// number >= 4) with the paper's material: friction, rotations and local
// damping on, ψ_ε = 0° loading at ‖D‖ = 167 1/s, Δt = 1.2e-7 s.
//
// The dense packings are made once (frictionless fast compression of a
// generated sample to 500 kPa) and cached as text packings in
// $GRANASYM_BENCH_CACHE (default: the system temporary folder).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>

#include "common/state_measures.h"
#include "dem/contact_statistics.h"
#include "dem/engine.h"
#include "dem/packing.h"

namespace granasym::dem {
namespace {

Material PaperMaterial() { return Material{}; }  // E 500 MPa, ν 0.3, φ 0.5 rad, χ 0.5

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
  if (std::filesystem::exists(path)) return cache[count] = Packing::ReadText(path);
  GenerationOptions options;
  options.count = count;
  options.cell_size = 31e-3 * std::cbrt(count / 150000.0);
  const Packing loose = GeneratePacking(GrainSizeDistribution::Default(), options);
  Material frictionless = PaperMaterial();
  frictionless.friction_angle = 0.0;
  Engine::Options engine_options;
  engine_options.threads = 2;
  Engine engine(loose, frictionless, engine_options);
  const AxisymmetricRate rate = AxisymmetricRate::FromAngle(0.0, 1000.0);
  engine.SetVelocityGradient({-rate.axial, -rate.radial, -rate.radial});
  for (int64_t step = 0;; ++step) {
    const bool check = step % 50 == 0;
    engine.Step({check, false});
    if (check && AxisymmetricFromTensor(engine.sums().stress).mean() > 500e3) break;
  }
  // Let the packing settle without straining.
  engine.SetVelocityGradient({0, 0, 0});
  for (int step = 0; step < 2000; ++step) engine.Step();
  Packing dense = engine.CurrentPacking();
  dense.WriteText(path);
  return cache[count] = dense;
}

void BM_DemStep(benchmark::State& state) {
  const size_t count = static_cast<size_t>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const Packing& packing = DensePacking(count);
  Engine::Options options;
  options.threads = threads;
  Engine engine(packing, PaperMaterial(), options);
  const AxisymmetricRate rate = AxisymmetricRate::FromAngle(0.0, 167.0);
  engine.SetVelocityGradient({-rate.axial, -rate.radial, -rate.radial});
  for (int step = 0; step < 50; ++step) engine.Step();  // build lists, warm caches
  for (auto _ : state) engine.Step();
  const ContactStatistics contacts = MeasureContacts(engine, nullptr);
  const double particle_steps = static_cast<double>(state.iterations()) * count;
  state.counters["particle_steps_per_s"] =
      benchmark::Counter(particle_steps, benchmark::Counter::kIsRate);
  state.counters["us_per_particle_step"] = benchmark::Counter(
      particle_steps / 1e6, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["coordination"] = contacts.coordination;
  state.counters["pairs_per_particle"] =
      static_cast<double>(engine.neighbors().pair_count()) / count;
}

BENCHMARK(BM_DemStep)
    ->ArgNames({"N", "threads"})
    ->Args({10000, 1})
    ->Args({10000, 2})
    ->Args({150000, 1})
    ->Args({150000, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

}  // namespace
}  // namespace granasym::dem

BENCHMARK_MAIN();
