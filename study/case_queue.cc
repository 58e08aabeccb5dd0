#include "study/case_queue.h"

#include "common/error.h"

namespace granasym::study {

bool CaseQueue::Later::operator()(const std::pair<double, int>& a,
                                  const std::pair<double, int>& b) const {
  ++queue->operations_;
  // std::priority_queue pops its greatest element: most work, then lowest index.
  if (a.first != b.first) return a.first < b.first;
  return a.second > b.second;
}

CaseQueue::CaseQueue(const Plan& plan, const std::vector<int>& selected)
    : plan_(plan),
      in_shard_(plan.cases.size(), 0),
      work_(plan.cases.size(), 0.0),
      below_(plan.cases.size(), 0.0),
      ready_(Later{this}) {
  for (int k : selected) {
    const PlannedCase& c = plan.cases[static_cast<size_t>(k)];
    GRANASYM_CHECK(c.parent < k) << "the plan orders parents before children";
    in_shard_[static_cast<size_t>(k)] = 1;
    work_[static_cast<size_t>(k)] = static_cast<double>(c.particles) * c.estimated_steps;
  }
  // Children come after their parents: one pass from the end sums the work below.
  for (auto it = selected.rbegin(); it != selected.rend(); ++it) {
    const size_t k = static_cast<size_t>(*it);
    below_[k] += work_[k];
    const int parent = plan.cases[k].parent;
    if (parent >= 0 && in_shard(parent)) below_[static_cast<size_t>(parent)] += below_[k];
    ++operations_;
  }
  for (int k : selected) {
    const int parent = plan.cases[static_cast<size_t>(k)].parent;
    if (parent < 0 || !in_shard(parent)) ready_.emplace(below_[static_cast<size_t>(k)], k);
  }
}

int CaseQueue::Pop() {
  GRANASYM_CHECK(!ready_.empty()) << "Pop on an empty case queue";
  const int k = ready_.top().second;
  ready_.pop();
  return k;
}

void CaseQueue::Release(int k) {
  for (int child : plan_.cases[static_cast<size_t>(k)].children) {
    ++operations_;
    if (in_shard(child)) ready_.emplace(below_[static_cast<size_t>(child)], child);
  }
}

std::vector<int> CaseQueue::Descendants(int k) const {
  std::vector<int> below;
  std::vector<int> stack(plan_.cases[static_cast<size_t>(k)].children);
  while (!stack.empty()) {
    const int c = stack.back();
    stack.pop_back();
    ++operations_;
    if (!in_shard(c)) continue;
    below.push_back(c);
    for (int g : plan_.cases[static_cast<size_t>(c)].children) stack.push_back(g);
  }
  return below;
}

std::vector<int> CaseQueue::TakeAll() {
  std::vector<int> taken;
  taken.reserve(ready_.size());
  while (!ready_.empty()) taken.push_back(Pop());
  return taken;
}

}  // namespace granasym::study
