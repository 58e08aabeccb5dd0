// The order in which a shard's cases start: the ready case (its parent
// finished or outside the shard) with the most estimated work below it
// first, so that the critical path starts early. The work below every case
// is summed once, and the ready cases are kept in a heap: a shard of N cases
// is scheduled in O(N log N) (the runner holds its lock only for a pop or a
// release), whatever the shape of the tree.
#pragma once

#include <cstdint>
#include <queue>
#include <utility>
#include <vector>

#include "study/plan.h"

namespace granasym::study {

class CaseQueue {
 public:
  // `selected`: the shard's cases (Plan::Shard), parents before children.
  CaseQueue(const Plan& plan, const std::vector<int>& selected);

  bool empty() const { return ready_.empty(); }
  size_t ready() const { return ready_.size(); }
  // The ready case with the most work below it (the lowest index among
  // equals); the queue must not be empty.
  int Pop();
  // Case k finished with a state to start from: its children in the shard
  // become ready.
  void Release(int k);
  // Every case of the shard that is neither ready nor released yet below k
  // (k's descendants in the shard), for a case that ended without a state.
  std::vector<int> Descendants(int k) const;
  // Removes every ready case and returns them (a stop request).
  std::vector<int> TakeAll();

  bool in_shard(int k) const { return in_shard_[static_cast<size_t>(k)] != 0; }
  // The estimated work of case k alone and of k with everything below it
  // in the shard (particle-steps).
  double work(int k) const { return work_[static_cast<size_t>(k)]; }
  double work_below(int k) const { return below_[static_cast<size_t>(k)]; }
  // Elementary steps taken so far (heap comparisons and case visits): what
  // the tests count to show the scheduling near-linear.
  int64_t operations() const { return operations_; }

 private:
  struct Later {
    const CaseQueue* queue;
    bool operator()(const std::pair<double, int>& a, const std::pair<double, int>& b) const;
  };

  const Plan& plan_;
  std::vector<char> in_shard_;
  std::vector<double> work_, below_;
  mutable int64_t operations_ = 0;
  std::priority_queue<std::pair<double, int>, std::vector<std::pair<double, int>>, Later> ready_;
};

}  // namespace granasym::study
