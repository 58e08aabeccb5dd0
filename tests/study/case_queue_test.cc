// The order of a shard's cases (study/case_queue.h): the critical path
// first, every case once, and scheduling near-linear in the number of cases
// (counted in elementary operations, not timed).
#include "study/case_queue.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <vector>

namespace granasym::study {
namespace {

// A plan of `count` cases without scenes: case 0 is the root; every other
// case's parent is (k - 1) / fanout (fanout 0: every case from the sample).
Plan Synthetic(int count, int fanout) {
  Plan plan;
  plan.cases.resize(static_cast<size_t>(count));
  for (int k = 0; k < count; ++k) {
    PlannedCase& c = plan.cases[static_cast<size_t>(k)];
    c.id = "r1/c" + std::to_string(k);
    c.particles = 100;
    c.estimated_steps = 1000.0 + (k * 7919) % 1000;  // unequal work
    if (fanout > 0 && k > 0) {
      c.parent = (k - 1) / fanout;
      plan.cases[static_cast<size_t>(c.parent)].children.push_back(k);
    }
  }
  return plan;
}

std::vector<int> All(const Plan& plan) {
  std::vector<int> all(plan.cases.size());
  std::iota(all.begin(), all.end(), 0);
  return all;
}

// Runs the whole queue as one worker would: pop, finish, release.
int64_t Schedule(const Plan& plan, std::vector<int>* order = nullptr) {
  CaseQueue queue(plan, All(plan));
  while (!queue.empty()) {
    const int k = queue.Pop();
    if (order) order->push_back(k);
    queue.Release(k);
  }
  return queue.operations();
}

TEST(CaseQueue, EveryCaseOnceParentsFirstCriticalPathFirst) {
  const Plan plan = Synthetic(2000, 3);
  std::vector<int> order;
  Schedule(plan, &order);
  ASSERT_EQ(order.size(), plan.cases.size());
  std::vector<int> position(order.size());
  for (size_t k = 0; k < order.size(); ++k) position[static_cast<size_t>(order[k])] = k;
  for (size_t k = 1; k < plan.cases.size(); ++k) {
    EXPECT_LT(position[static_cast<size_t>(plan.cases[k].parent)], position[k]) << k;
  }
  // The root's children: the one with the most work below it starts first.
  CaseQueue queue(plan, All(plan));
  EXPECT_EQ(queue.Pop(), 0);
  queue.Release(0);
  const std::vector<int>& children = plan.cases[0].children;
  const int heaviest = *std::max_element(children.begin(), children.end(), [&](int a, int b) {
    return queue.work_below(a) < queue.work_below(b);
  });
  EXPECT_EQ(queue.Pop(), heaviest);
  // Work below the root: everything.
  double total = 0;
  for (size_t k = 0; k < plan.cases.size(); ++k) total += queue.work(static_cast<int>(k));
  EXPECT_DOUBLE_EQ(queue.work_below(0), total);
}

// Twice the cases take less than three times the operations, for a star (one
// NCL and every case forked from it: all ready at once), a wide tree, a
// chain and cases all from the sample. Walking each ready case's subtree
// on every pick (what the scheduler did) takes N^2 on a star.
TEST(CaseQueue, SchedulingIsNearLinearInTheCases) {
  for (const int fanout : {0, 1, 4, 1000000}) {
    const int64_t small = Schedule(Synthetic(50000, fanout));
    const int64_t large = Schedule(Synthetic(100000, fanout));
    const double ratio = static_cast<double>(large) / static_cast<double>(small);
    EXPECT_LT(ratio, 3.0) << "fanout " << fanout << ": " << small << " then " << large;
    EXPECT_GE(ratio, 1.9) << "fanout " << fanout << ": " << small << " then " << large;
    // n log2 n bounds it: about 2 comparisons per heap level.
    EXPECT_LT(large, 100000LL * 60) << "fanout " << fanout;
  }
}

TEST(CaseQueue, AShardSchedulesItsOwnCasesOnly) {
  const Plan plan = Synthetic(100, 2);
  // Case 5 and its subtree, without its ancestors (computed by another shard).
  std::vector<int> selected;
  std::vector<int> stack{5};
  while (!stack.empty()) {
    const int k = stack.back();
    stack.pop_back();
    selected.push_back(k);
    for (int c : plan.cases[static_cast<size_t>(k)].children) stack.push_back(c);
  }
  std::sort(selected.begin(), selected.end());
  CaseQueue queue(plan, selected);
  EXPECT_EQ(queue.ready(), 1u);
  EXPECT_EQ(queue.Descendants(5).size(), selected.size() - 1);
  EXPECT_FALSE(queue.in_shard(0));
  size_t popped = 0;
  while (!queue.empty()) {
    queue.Release(queue.Pop());
    ++popped;
  }
  EXPECT_EQ(popped, selected.size());
  EXPECT_TRUE(queue.TakeAll().empty());
}

}  // namespace
}  // namespace granasym::study
