// Cost of writing and reading the exact engine state of a run the paper's
// size (150 000 spheres, the checkpoint's and the result's largest part) and
// a time series of 2 000 rows × 40 columns: what a checkpoint costs, with the
// checksums every dataset carries (common/hdf5_file.h).
//
// The state is synthetic (random positions in a unit cell, eight list entries
// per sphere: the half list of a dense packing with the default skin); only
// its sizes matter for the file's cost. The file goes to
// $GRANASYM_BENCH_CACHE (default: the system temporary folder).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>

#include "common/hdf5_file.h"
#include "common/time_series.h"
#include "dem/engine.h"
#include "dem/run_record.h"

namespace granasym::dem {
namespace {

constexpr int kListEntriesPerSphere = 8;

Engine::State SyntheticState(size_t count) {
  std::mt19937_64 random(1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Engine::State state;
  state.position.resize(count);
  state.velocity.resize(count);
  state.spin.resize(count);
  state.id.resize(count);
  for (size_t i = 0; i < count; ++i) {
    state.position[i] = {unit(random), unit(random), unit(random), 1e-4 * (1 + unit(random))};
    state.velocity[i] = {1e-3 * unit(random), 1e-3 * unit(random), 1e-3 * unit(random), 1e5};
    state.spin[i] = {unit(random), unit(random), unit(random), 1e12};
    state.id[i] = static_cast<int64_t>(i);
  }
  state.cell = {0.031, 0.031, 0.031};
  NeighborList::State& list = state.neighbors;
  list.offsets.resize(count + 1);
  for (size_t i = 0; i < count; ++i) {
    list.offsets[i + 1] = list.offsets[i];
    for (int k = 1; k <= kListEntriesPerSphere && i + k < count; ++k) {
      list.neighbors.push_back(static_cast<int32_t>(i + k));
      ++list.offsets[i + 1];
    }
  }
  list.shear.assign(list.neighbors.size(), Vec3{1e-7, 2e-7, 3e-7});
  list.build_positions = state.position;
  list.build_cell = state.cell;
  list.skin = 3e-5;
  list.max_radius = 2e-4;
  return state;
}

TimeSeries SyntheticSeries(size_t rows, size_t columns) {
  std::vector<TimeSeries::Column> names;
  for (size_t c = 0; c < columns; ++c) names.push_back({"c" + std::to_string(c), "1", ""});
  TimeSeries series(names);
  for (size_t r = 0; r < rows; ++r) series.AddRow(std::vector<double>(columns, 0.5 * r));
  return series;
}

std::string BenchPath(const std::string& name) {
  const char* dir = std::getenv("GRANASYM_BENCH_CACHE");
  const std::filesystem::path base = dir ? dir : std::filesystem::temp_directory_path();
  return (base / ("granasym_" + name)).string();
}

void BM_WriteEngineState(benchmark::State& state) {
  const size_t count = static_cast<size_t>(state.range(0));
  const Engine::State engine_state = SyntheticState(count);
  const TimeSeries series = SyntheticSeries(2000, 40);
  const std::string path = BenchPath("bench_state.h5");
  for (auto _ : state) {
    Hdf5File file = Hdf5File::CreateAtomic(path);
    WriteEngineState(file, "/engine", engine_state, 2);
    series.Write(file, "/series");
    file.Commit();
  }
  const double bytes = static_cast<double>(std::filesystem::file_size(path));
  state.counters["file_MB"] = bytes / 1e6;
  state.counters["MB_per_s"] = benchmark::Counter(
      bytes * static_cast<double>(state.iterations()) / 1e6, benchmark::Counter::kIsRate);
  std::filesystem::remove(path);
}
BENCHMARK(BM_WriteEngineState)->Arg(150000)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ReadEngineState(benchmark::State& state) {
  const size_t count = static_cast<size_t>(state.range(0));
  const std::string path = BenchPath("bench_state_read.h5");
  {
    Hdf5File file = Hdf5File::CreateAtomic(path);
    WriteEngineState(file, "/engine", SyntheticState(count), 2);
    SyntheticSeries(2000, 40).Write(file, "/series");
    file.Commit();
  }
  for (auto _ : state) {
    const Hdf5File file = Hdf5File::OpenRead(path);
    benchmark::DoNotOptimize(ReadEngineState(file, "/engine"));
    benchmark::DoNotOptimize(TimeSeries::Read(file, "/series"));
  }
  const double bytes = static_cast<double>(std::filesystem::file_size(path));
  state.counters["file_MB"] = bytes / 1e6;
  state.counters["MB_per_s"] = benchmark::Counter(
      bytes * static_cast<double>(state.iterations()) / 1e6, benchmark::Counter::kIsRate);
  std::filesystem::remove(path);
}
BENCHMARK(BM_ReadEngineState)->Arg(150000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace granasym::dem
BENCHMARK_MAIN();
