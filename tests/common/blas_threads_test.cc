#include "common/blas_threads.h"

#include <dlfcn.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <iterator>

namespace granasym {
namespace {

// The threads of this process.
int ThreadCount() {
  const std::filesystem::directory_iterator tasks("/proc/self/task");
  return static_cast<int>(std::distance(begin(tasks), end(tasks)));
}

// OpenBLAS is loaded here as the program loads it through libblas.so.3 where
// the system's BLAS is OpenBLAS; this test binary links no BLAS, so that
// before the load there is none.
TEST(BlasThreads, OpenBlasIsKeptOnOneThreadAndItsPoolEnded) {
  ASSERT_EQ(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"), nullptr);
  EXPECT_EQ(KeepBlasSerial(), BlasPool::kAbsent);
  unsetenv("OPENBLAS_NUM_THREADS");
  unsetenv("GOTO_NUM_THREADS");
  unsetenv("OMP_NUM_THREADS");
  void* openblas = dlopen("libopenblas.so.0", RTLD_NOW | RTLD_GLOBAL);
  if (openblas == nullptr) GTEST_SKIP() << "OpenBLAS is not installed: " << dlerror();
  using GetThreads = int (*)();
  using Dot = double (*)(const int*, const double*, const int*, const double*, const int*);
  auto get_threads = reinterpret_cast<GetThreads>(dlsym(openblas, "openblas_get_num_threads"));
  auto parallel = reinterpret_cast<GetThreads>(dlsym(openblas, "openblas_get_parallel"));
  auto dot = reinterpret_cast<Dot>(dlsym(openblas, "ddot_"));
  ASSERT_NE(get_threads, nullptr);
  ASSERT_NE(parallel, nullptr);
  ASSERT_NE(dot, nullptr);
  if (parallel() != 1) {
    // A serial or OpenMP build has no pool of its own: left as it is.
    const int threads = get_threads(), before = ThreadCount();
    EXPECT_EQ(KeepBlasSerial(), BlasPool::kNoPool);
    EXPECT_EQ(get_threads(), threads);
    EXPECT_EQ(ThreadCount(), before);
    return;
  }
  // Its pool: one thread fewer than the cores (the caller is the first).
  const int pool = get_threads() - 1;
  const int before = ThreadCount();
  ASSERT_GE(before, 1 + pool);

  // The user's setting stands.
  setenv("OPENBLAS_NUM_THREADS", "2", 1);
  EXPECT_EQ(KeepBlasSerial(), BlasPool::kLeftToUser);
  EXPECT_EQ(get_threads(), pool + 1);
  EXPECT_EQ(ThreadCount(), before);
  unsetenv("OPENBLAS_NUM_THREADS");

  EXPECT_EQ(KeepBlasSerial(), BlasPool::kStopped);
  EXPECT_EQ(get_threads(), 1);
  EXPECT_EQ(ThreadCount(), before - pool);
  // BLAS still works, on the calling thread, and starts no pool again.
  const int n = 3, one = 1;
  const double x[] = {1, 2, 3}, y[] = {4, 5, 6};
  EXPECT_EQ(dot(&n, x, &one, y, &one), 32.0);
  EXPECT_EQ(ThreadCount(), before - pool);
}

}  // namespace
}  // namespace granasym
