#include "dem/near_list.h"

#include <omp.h>

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "dem/minimum_image.h"

namespace granasym::dem {

void NearList::Build(const NeighborList& list, const std::vector<Vec4>& s,
                     const std::array<double, 3>& cell, double skin, int threads, History history) {
  GRANASYM_CHECK(list.built() && threads >= 1 && skin > 0);
  const int64_t n = static_cast<int64_t>(s.size());
  const int64_t* offsets = list.offsets().data();
  const int32_t* owner = list.owners().data();
  const int32_t* neighbor = list.neighbors().data();
  const double lx = cell[0], ly = cell[1], lz = cell[2];
  // A pair whose |l|² rounds just above the cut may lie just below it: the
  // cut is widened far beyond the rounding, so that every pair left out has
  // a gap of at least `skin`.
  constexpr double kWiden = 1.0 + 1e-12;
  pairs_.resize(threads);
  build_positions_.resize(s.size());
  int64_t touching = 0;
#pragma omp parallel num_threads(threads) reduction(+ : touching)
  {
    const int t = omp_get_thread_num();
    const int64_t begin = n * t / threads, end = n * (t + 1) / threads;
    std::copy(s.begin() + begin, s.begin() + end, build_positions_.begin() + begin);
    const int64_t first = offsets[begin], last = offsets[end];
    Pairs& mine = pairs_[t];
    const size_t listed = static_cast<size_t>(last - first);
    if (mine.p.size() < listed) {
      mine.i.resize(listed);
      mine.j.resize(listed);
      mine.p.resize(listed);
    }
    int64_t count = 0;
    for (int64_t p = first; p < last; ++p) {
      const int32_t i = owner[p], j = neighbor[p];
      const Vec4 pi = s[i], pj = s[j];
      const Vec3 l = Branch(pi, pj, lx, ly, lz);
      const double reach = pi.w + pj.w, cut = reach + skin, distance2 = Dot(l, l);
      const bool near = distance2 < kWiden * (cut * cut);
      touching += distance2 < reach * reach;
      // Compaction without a data-dependent branch (near or not is close to
      // a coin toss); a left-out pair is not touching, so one that held a
      // history forgets it, as the force pass would now (rare: it touched
      // at the last evaluation).
      mine.i[count] = i;
      mine.j[count] = j;
      mine.p[count] = p;
      count += near;
      if (!near && history.loaded != nullptr && history.loaded[p] != 0) {
        history.loaded[p] = 0;
        history.shear[p] = Vec3{};
        if (history.rolling != nullptr) history.rolling[p] = Vec3{};
      }
    }
    mine.count = count;
    mine.remote.clear();
    if (end < n) {
      std::vector<uint8_t> reached(static_cast<size_t>(n - end), 0);
      for (int64_t q = 0; q < count; ++q) {
        const int32_t j = mine.j[q];
        if (j >= end) reached[j - end] = 1;
      }
      for (int64_t k = 0; k < n - end; ++k) {
        if (reached[k] != 0) mine.remote.push_back(static_cast<int32_t>(end + k));
      }
    }
  }
  build_cell_ = cell;
  skin_ = skin;
  max_radius_ = list.max_radius();
  listed_ = static_cast<int64_t>(list.pair_count());
  touching_ = touching;
  built_ = true;
  ++builds_;
}

bool NearList::NeedsRebuild(double max_displacement, const std::array<double, 3>& cell) const {
  return !built_ ||
         VerletListMayMissContact(max_displacement, cell, build_cell_, max_radius_, skin_);
}

double NearList::MaxDisplacement(const std::vector<Vec4>& s, const std::array<double, 3>& cell,
                                 int threads) const {
  return LargestDisplacement(s, build_positions_, cell, threads);
}

double NearList::MetricFactor() const { return VerletMetricFactor(max_radius_, skin_); }

double NearList::SkinUsed(double max_displacement, const std::array<double, 3>& cell) const {
  return VerletSkinUsed(max_displacement, cell, build_cell_, max_radius_, skin_);
}

double NearList::CheapestSkin(double skin, double overhead, int64_t near, int64_t touching,
                              double used_per_step, double smallest, double largest) {
  const double band = static_cast<double>(near - touching);
  double cheapest;
  if (band <= 0) {
    cheapest = 2.0 * skin;  // no pair within the skin but touching ones: widen
  } else if (!(used_per_step > 0)) {
    cheapest = 0.5 * skin;  // nothing moves: every listed pair outside touching is waste
  } else {
    cheapest = std::sqrt(overhead * used_per_step * skin / band);
  }
  cheapest = std::clamp(cheapest, 0.5 * skin, 2.0 * skin);
  return std::clamp(cheapest, smallest, largest);
}

int64_t NearList::pair_count() const {
  int64_t count = 0;
  for (const Pairs& p : pairs_) count += p.size();
  return count;
}

}  // namespace granasym::dem
