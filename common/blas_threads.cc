#include "common/blas_threads.h"

#include <dlfcn.h>

#include <cstdlib>

namespace granasym {

BlasPool KeepBlasSerial() {
  // Looked up, not linked: which BLAS the system's libblas.so.3 is, is the
  // system's choice (update-alternatives), and OpenBLAS may be absent.
  using SetThreads = void (*)(int);
  using Shutdown = int (*)();
  using Parallel = int (*)();
  auto set_threads = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  // OpenBLAS's own exported shutdown (it ends the pool before a fork too).
  auto shutdown = reinterpret_cast<Shutdown>(dlsym(RTLD_DEFAULT, "blas_thread_shutdown_"));
  // 0: serial build, 1: its own pthreads pool, 2: OpenMP.
  auto parallel = reinterpret_cast<Parallel>(dlsym(RTLD_DEFAULT, "openblas_get_parallel"));
  if (set_threads == nullptr) return BlasPool::kAbsent;
  if (parallel == nullptr || parallel() != 1) return BlasPool::kNoPool;
  if (std::getenv("OPENBLAS_NUM_THREADS") != nullptr || std::getenv("GOTO_NUM_THREADS") != nullptr)
    return BlasPool::kLeftToUser;
  set_threads(1);
  if (shutdown != nullptr) shutdown();
  return BlasPool::kStopped;
}

}  // namespace granasym
