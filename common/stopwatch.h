// Wall-clock time of a piece of work (timing fields of summaries and
// progress), and a thread's processor time.
#pragma once

#include <time.h>

#include <chrono>

namespace granasym {

// Wall-clock seconds since construction.
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double Seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

// Processor seconds the calling thread has used (CLOCK_THREAD_CPUTIME_ID):
// the work of a case run on one thread, whatever else shares the machine or
// however long the process was stopped.
inline double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace granasym
