// How a study uses the machine: cases run at once (jobs) and OpenMP threads
// per case. The thread count is part of every case's key (results are
// bit-identical for a fixed count), so the choice depends only on the sample
// size and the machine (hardware threads, physical memory), never on its
// load of the moment.
#pragma once

#include <cstdint>
#include <string>

namespace granasym::study {

struct Parallelism {
  int jobs = 1;
  int threads = 1;
  std::string reason;  // one line for the study's header
};

// Measured on 2 cores (bench/README.md, "Studies: cases at once or threads
// per case"): single-thread cases side by side give more cases per hour than
// one case on both threads, 1.38x for the small paper study (3 000 spheres)
// and 1.24x for two 150 000-sphere runs of the default scene. So a study runs
// one single-thread case per hardware thread, as many as the memory holds.
// Peak of a run: ~1 050 B/sphere at 150 000 (the default scene, 1 thread;
// ~100 of them the near list's pairs and positions).
inline constexpr double kCaseBytesPerSphere = 1152;

// `jobs`/`threads` of 0 are chosen; a value given by the user is kept, and the
// other fills the hardware threads (at least 1). `memory_bytes` of 0: unknown.
Parallelism ChooseParallelism(int hardware_threads, double memory_bytes, int64_t spheres, int jobs,
                              int threads);

}  // namespace granasym::study
