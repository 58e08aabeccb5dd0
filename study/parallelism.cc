#include "study/parallelism.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace granasym::study {

Parallelism ChooseParallelism(int hardware_threads, double memory_bytes, int64_t spheres, int jobs,
                              int threads) {
  const int hardware = std::max(1, hardware_threads);
  Parallelism p;
  if (jobs > 0 && threads > 0) {
    p.jobs = jobs;
    p.threads = threads;
    p.reason = "as given";
    return p;
  }
  if (jobs > 0) {
    p.jobs = jobs;
    p.threads = std::max(1, hardware / jobs);
    p.reason =
        fmt::format("--jobs {} given: {} hardware threads shared among them", jobs, hardware);
    return p;
  }
  if (threads > 0) {
    p.threads = threads;
    p.jobs = std::max(1, hardware / threads);
    p.reason = fmt::format("--threads {} given: as many cases as fill {} hardware threads", threads,
                           hardware);
    return p;
  }
  // One single-thread case per hardware thread, as many as the memory holds
  // (half of it, the rest for the system and the cases' files).
  const double per_case = kCaseBytesPerSphere * static_cast<double>(std::max<int64_t>(spheres, 1));
  const int fit =
      memory_bytes > 0
          ? static_cast<int>(std::min<double>(hardware, std::floor(0.5 * memory_bytes / per_case)))
          : hardware;
  p.jobs = std::max(1, fit);
  p.threads = std::max(1, hardware / p.jobs);
  p.reason = p.jobs == hardware ? fmt::format(
                                      "single-thread cases side by side: more cases per hour than "
                                      "threads per case")
                                : fmt::format(
                                      "{} cases of {} spheres (~{:.2g} GB each) fit in memory: {} "
                                      "threads each",
                                      p.jobs, spheres, per_case / 1e9, p.threads);
  return p;
}

}  // namespace granasym::study
