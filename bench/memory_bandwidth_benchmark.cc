// The machine's memory as the DEM engine's passes see it, on 1 and 2
// threads:
// - BM_Memory: bandwidth of a read pass (a sum), a copy and a triad
//   (a = b + s c) over arrays of doubles, at sizes that live in L2, in L3 and
//   in memory. The engine's per-particle passes (the integrator: ~160 bytes
//   read and ~96 written per particle) are compared against these rates in
//   bench/README.md.
// - BM_Latency: the time of one load that depends on the one before, through
//   a random cycle over the cache lines of an array, by array size. Where a
//   virtual machine's sysfs names no caches this is how their sizes are
//   read: the time steps up past each level (the DEM's random reads of the
//   spheres j pay these latencies).
// - BM_HandOff: one way of a cache line handed between two threads that
//   take turns writing it (each waits for the other's value, then writes its
//   own), pinned to the first two CPUs the process may use. It is what a
//   line written by one thread of the engine and read by the other costs,
//   and what a barrier costs at least; on a virtual machine it shows
//   whether the two vCPUs share a cache at the moment.
// - BM_Gather: loads that do not depend on each other, at random places of
//   an array of the thread's own, by array size, on 1 and 2 threads: what
//   the DEM's gathers cost when nothing is handed over. A second thread
//   that makes each thread's loads dearer shares a cache level or the
//   memory interface with the first.
// - BM_Arithmetic: independent multiply-adds in registers on 1 and 2
//   threads. Two vCPUs that are the two hardware threads of one core halve
//   each other's rate here; two cores do not.
#include <benchmark/benchmark.h>
#include <omp.h>
#include <pthread.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <numeric>
#include <random>
#include <thread>
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

// One cache line of the chase: the index of the next line, and padding.
struct alignas(64) Line {
  int64_t next;
  char padding[56];
};

void BM_Latency(benchmark::State& state) {
  const int64_t lines = state.range(0) / static_cast<int64_t>(sizeof(Line));
  // A single random cycle through every line (Sattolo's shuffle of the
  // order, then each line names its successor), so that neither the
  // hardware prefetchers nor a short sub-cycle can help.
  std::vector<int64_t> order(static_cast<size_t>(lines));
  std::iota(order.begin(), order.end(), 0);
  std::mt19937_64 random(12345);
  for (int64_t k = lines - 1; k > 0; --k) {
    std::uniform_int_distribution<int64_t> pick(0, k - 1);
    std::swap(order[k], order[pick(random)]);
  }
  std::vector<Line> chase(static_cast<size_t>(lines));
  for (int64_t k = 0; k < lines; ++k) chase[order[k]].next = order[(k + 1) % lines];
  constexpr int64_t kLoads = 1 << 20;
  int64_t at = 0;
  for (int64_t k = 0; k < lines; ++k) at = chase[at].next;  // warm the caches and the TLB
  for (auto _ : state) {
    for (int64_t k = 0; k < kLoads; ++k) at = chase[at].next;
    benchmark::DoNotOptimize(at);
  }
  state.counters["ns_per_load"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * kLoads,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

BENCHMARK(BM_Latency)
    ->ArgName("bytes")
    ->RangeMultiplier(2)
    ->Range(64 << 10, 256 << 20)
    ->UseRealTime();

// Pins the calling thread to one CPU.
void PinTo(int cpu) {
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(cpu, &one);
  pthread_setaffinity_np(pthread_self(), sizeof one, &one);
}

void BM_HandOff(benchmark::State& state) {
  constexpr int64_t kHandOffs = 1 << 18;  // per iteration, both ways together
  // The CPUs this thread may use, read before it is pinned (a thread it
  // starts inherits its mask) and given back at the end.
  cpu_set_t allowed;
  if (pthread_getaffinity_np(pthread_self(), sizeof allowed, &allowed) != 0) {
    state.SkipWithError("cannot read the CPU affinity");
    return;
  }
  // The first two CPUs it may use.
  int cpus[2] = {-1, -1};
  for (int cpu = 0, found = 0; cpu < CPU_SETSIZE && found < 2; ++cpu) {
    if (CPU_ISSET(cpu, &allowed)) cpus[found++] = cpu;
  }
  if (cpus[1] < 0) {
    state.SkipWithError("needs two CPUs (the process may use one)");
    return;
  }
  alignas(64) std::atomic<int64_t> turn{0};
  std::atomic<bool> stop{false};
  // The partner answers every odd value with the next even one.
  std::thread partner([&] {
    PinTo(cpus[1]);
    int64_t expected = 1;
    while (true) {
      while (turn.load(std::memory_order_acquire) != expected) {
        if (stop.load(std::memory_order_relaxed)) return;
      }
      turn.store(expected + 1, std::memory_order_release);
      expected += 2;
    }
  });
  PinTo(cpus[0]);
  int64_t next = 0;
  for (auto _ : state) {
    for (int64_t k = 0; k < kHandOffs; k += 2) {
      while (turn.load(std::memory_order_acquire) != next) {
      }
      turn.store(next + 1, std::memory_order_release);
      next += 2;
    }
  }
  while (turn.load(std::memory_order_acquire) != next) {
  }
  stop.store(true, std::memory_order_relaxed);
  partner.join();
  pthread_setaffinity_np(pthread_self(), sizeof allowed, &allowed);
  state.counters["ns_one_way"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * kHandOffs,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

BENCHMARK(BM_HandOff)->UseRealTime();

void BM_Gather(benchmark::State& state) {
  const int64_t n = state.range(0) / static_cast<int64_t>(sizeof(double));
  const int threads = static_cast<int>(state.range(1));
  constexpr int kIndices = 1 << 16;
  constexpr int kRounds = 16;  // passes over the indices per iteration
  // Each thread's array and indices, written (first touched) by that thread.
  std::vector<std::vector<double>> values(threads);
  std::vector<std::vector<uint32_t>> indices(threads);
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num();
    values[t].assign(static_cast<size_t>(n), 1.0);
    std::mt19937 random(static_cast<uint32_t>(t) + 1);
    std::uniform_int_distribution<int64_t> pick(0, n - 1);
    indices[t].resize(kIndices);
    for (uint32_t& k : indices[t]) k = static_cast<uint32_t>(pick(random));
  }
  double sink = 0;
  for (auto _ : state) {
    double sum = 0;
#pragma omp parallel num_threads(threads) reduction(+ : sum)
    {
      const int t = omp_get_thread_num();
      const double* v = values[t].data();
      const uint32_t* at = indices[t].data();
      // Four sums, so that the loads, not the additions, set the pace.
      double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
      for (int r = 0; r < kRounds; ++r) {
        for (int k = 0; k < kIndices; k += 4) {
          s0 += v[at[k]];
          s1 += v[at[k + 1]];
          s2 += v[at[k + 2]];
          s3 += v[at[k + 3]];
        }
      }
      sum += (s0 + s1) + (s2 + s3);
    }
    sink += sum;
  }
  benchmark::DoNotOptimize(sink);
  state.counters["ns_per_load"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * kRounds * kIndices,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);  // per thread
}

BENCHMARK(BM_Gather)
    ->ArgNames({"bytes", "threads"})
    ->ArgsProduct({{256 << 10, 1 << 20, 4 << 20, 16 << 20}, {1, 2}})
    ->UseRealTime();

volatile double arithmetic_factor = 0.9999999;
volatile double arithmetic_term = 1e-7;

void BM_Arithmetic(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  constexpr int kChains = 64;  // independent: the compiler spreads them over vector registers
  constexpr int64_t kSteps = 1 << 20;
  const double factor = arithmetic_factor, term = arithmetic_term;
  double sink = 0;
  for (auto _ : state) {
    double sum = 0;
#pragma omp parallel num_threads(threads) reduction(+ : sum)
    {
      double chain[kChains];
      for (int k = 0; k < kChains; ++k) chain[k] = 1.0 + 1e-9 * k;
      for (int64_t step = 0; step < kSteps; ++step) {
#pragma omp simd
        for (int k = 0; k < kChains; ++k) chain[k] = chain[k] * factor + term;
      }
      for (int k = 0; k < kChains; ++k) sum += chain[k];
    }
    sink += sum;
  }
  benchmark::DoNotOptimize(sink);
  state.counters["Gflop_per_s_per_thread"] =
      benchmark::Counter(2.0 * kChains * kSteps * static_cast<double>(state.iterations()) / 1e9,
                         benchmark::Counter::kIsRate);
}

BENCHMARK(BM_Arithmetic)->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
