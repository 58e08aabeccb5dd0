#include "study/parallelism.h"

#include <gtest/gtest.h>

namespace granasym::study {
namespace {

constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

TEST(Parallelism, StudiesRunSingleThreadCasesSideBySide) {
  // Measured: more cases per hour at 3 000 and at 150 000 spheres.
  for (int64_t spheres : {3000, 150000}) {
    const Parallelism p = ChooseParallelism(2, 24 * kGiB, spheres, 0, 0);
    EXPECT_EQ(p.jobs, 2) << spheres;
    EXPECT_EQ(p.threads, 1) << spheres;
    EXPECT_NE(p.reason.find("side by side"), std::string::npos) << p.reason;
  }
  EXPECT_EQ(ChooseParallelism(16, 64 * kGiB, 150000, 0, 0).jobs, 16);
  EXPECT_EQ(ChooseParallelism(2, 0, 150000, 0, 0).jobs, 2);  // memory unknown
}

TEST(Parallelism, AsManyCasesAsTheMemoryHoldsTheRestAsThreads) {
  // 10 million spheres take ~11 GB per case: 24 GB hold one (half for cases).
  const Parallelism p = ChooseParallelism(2, 24 * kGiB, 10'000'000, 0, 0);
  EXPECT_EQ(p.jobs, 1);
  EXPECT_EQ(p.threads, 2);
  EXPECT_NE(p.reason.find("fit in memory"), std::string::npos) << p.reason;
  // 16 threads, memory for 4 cases: 4 jobs of 4 threads.
  const Parallelism q = ChooseParallelism(16, 2.0 * 4 * kCaseBytesPerSphere * 1e6, 1000000, 0, 0);
  EXPECT_EQ(q.jobs, 4);
  EXPECT_EQ(q.threads, 4);
}

TEST(Parallelism, AGivenValueIsKeptAndTheOtherFillsTheMachine) {
  Parallelism p = ChooseParallelism(8, 0, 3000, 0, 4);
  EXPECT_EQ(p.threads, 4);
  EXPECT_EQ(p.jobs, 2);
  p = ChooseParallelism(8, 0, 150000, 2, 0);
  EXPECT_EQ(p.jobs, 2);
  EXPECT_EQ(p.threads, 4);
  p = ChooseParallelism(2, 0, 150000, 3, 0);  // more jobs than threads: one thread each
  EXPECT_EQ(p.threads, 1);
  p = ChooseParallelism(2, 0, 3000, 1, 2);
  EXPECT_EQ(p.jobs, 1);
  EXPECT_EQ(p.threads, 2);
  EXPECT_EQ(p.reason, "as given");
  EXPECT_EQ(ChooseParallelism(0, 0, 3000, 0, 0).jobs, 1);  // unknown hardware: one thread
}

}  // namespace
}  // namespace granasym::study
