// The machine's memory bandwidth, as the DEM engine's passes see it: a read
// pass (a sum), a copy and a triad (a = b + s c) over arrays of doubles, at
// sizes that live in L2, in L3 and in memory, on 1 and 2 threads. The engine's
// per-particle passes (the integrator: ~160 bytes read and ~96 written per
// particle) are compared against these rates in bench/README.md.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cstdint>
#include <vector>

namespace {

enum Kind { kRead = 0, kCopy = 1, kTriad = 2 };

void BM_Memory(benchmark::State& state) {
  const int64_t bytes = state.range(0);
  const int threads = static_cast<int>(state.range(1));
  const Kind kind = static_cast<Kind>(state.range(2));
  const int64_t n = bytes / 8 / 3;  // three arrays share the size
  std::vector<double> a(n, 1.0), b(n, 2.0), c(n, 3.0);
  double sink = 0;
  for (auto _ : state) {
    double sum = 0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : sum)
    for (int64_t i = 0; i < n; ++i) {
      if (kind == kRead) {
        sum += b[i] + c[i];
      } else if (kind == kCopy) {
        a[i] = b[i];
      } else {
        a[i] = b[i] + 0.5 * c[i];
      }
    }
    sink += sum;
    benchmark::ClobberMemory();
  }
  benchmark::DoNotOptimize(sink);
  // Bytes that cross the memory interface per pass (a write also reads its line).
  const double moved = kind == kRead ? 16.0 * n : (kind == kCopy ? 24.0 * n : 32.0 * n);
  state.counters["GB_per_s"] =
      benchmark::Counter(moved * state.iterations() / 1e9, benchmark::Counter::kIsRate);
}

BENCHMARK(BM_Memory)
    ->ArgNames({"bytes", "threads", "kind"})
    ->ArgsProduct({{1 << 20, 8 << 20, 256 << 20}, {1, 2}, {kRead, kCopy, kTriad}})
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
