// The second, thinner level of the Verlet list: of the neighbour list's
// pairs, those whose gap was below a smaller skin when it was built. The
// force pass walks only these; the neighbour list (binned, with the contact
// history) is rebuilt as before, and this one, a pass over the neighbour
// list, whenever its own skin may be crossed. In a loose or slowly strained
// sample most listed pairs are far from touching, and the pass over them
// (two position gathers and a distance test per pair) is most of a step.
//
// Results do not depend on it: the pairs are kept in the neighbour list's
// order (the forces are summed in the same order), a pair it leaves out is
// not touching and cannot touch before the next build (the criterion of
// VerletListMayMissContact with this skin), and the build does to a left-out
// pair exactly what the force pass would at that step: a pair that held a
// history (it touched at the last evaluation) and is not touching forgets it.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "dem/neighbor_list.h"
#include "dem/vec.h"

namespace granasym::dem {

class NearList {
 public:
  // The contact history of the neighbour list's pairs that a build clears
  // for a left-out pair with loaded[p] != 0 (null: no history, e.g. no
  // friction): the flag, the shear force and (when tracked) the rolling
  // moment.
  struct History {
    uint8_t* loaded = nullptr;
    Vec3* shear = nullptr;
    Vec3* rolling = nullptr;
  };

  // Selects the pairs of `list` with |l| < r_i + r_j + skin at the scaled
  // positions `s`, per thread t of `threads` from the pairs of its particles
  // [n t/T, n (t+1)/T) (the force pass's split), in list order.
  void Build(const NeighborList& list, const std::vector<Vec4>& s,
             const std::array<double, 3>& cell, double skin, int threads, History history);
  // True when a pair left out may touch (and always before the first build).
  bool NeedsRebuild(double max_displacement, const std::array<double, 3>& cell) const;
  // The largest non-affine displacement since the build (one pass).
  double MaxDisplacement(const std::vector<Vec4>& s, const std::array<double, 3>& cell,
                         int threads) const;
  // VerletMetricFactor for this list's skin.
  double MetricFactor() const;
  // VerletSkinUsed since the build (m).
  double SkinUsed(double max_displacement, const std::array<double, 3>& cell) const;

  // The skin that makes a step cheapest, from what the last build saw: a
  // step walks the pairs of the list, about `touching` + (`near` − `touching`)
  // s'/s for a skin s' near the build's s (the pairs with a gap below s'),
  // and once every s'/c steps (c the skin used per step) comes the overhead
  // of a build, `overhead` in units of a step's visit of a pair. Their sum
  // is least at s* = sqrt(overhead c s / (near − touching)). The result
  // moves at most a factor 2 from `skin` per call and stays within
  // [smallest, largest].
  static double CheapestSkin(double skin, double overhead, int64_t near, int64_t touching,
                             double used_per_step, double smallest, double largest);
  // That overhead: the build's visit of each of the `listed` pairs and the
  // `measurements` passes over the `particles` that measured the
  // displacement since the previous build. A build's visit of a pair (its
  // gather, distance test and the kept pair's three writes) took 63
  // instructions against about 46 for the step's visit (callgrind, a loose
  // 5 000-sphere path), and the build also copies the positions: kBuildCost
  // 2; a measurement reads two positions per particle: kMeasureCost 1.
  static constexpr double kBuildCost = 2.0, kMeasureCost = 1.0;
  static double BuildOverhead(int64_t listed, int64_t particles, int64_t measurements) {
    return kBuildCost * static_cast<double>(listed) +
           kMeasureCost * static_cast<double>(particles) * static_cast<double>(measurements);
  }
  // Forgets the selection (a restored state, a rebuilt neighbour list).
  void Clear() { built_ = false; }

  // The selected pairs of one thread: p the index in the neighbour list (of
  // the pair's history), i and j its spheres (copied, so that the force pass
  // reads them in sequence rather than through p).
  struct Pairs {
    // The first `count` entries are the pairs; the arrays keep the capacity
    // of the largest build (no fill at each build).
    std::vector<int32_t> i, j;
    std::vector<int64_t> p;
    int64_t count = 0;
    // The spheres of other threads (j past the thread's own particles) that
    // its pairs reach, ascending, each once: the only ones whose halo entry
    // this thread can write (Engine's halo sum visits only these).
    std::vector<int32_t> remote;
    int64_t size() const { return count; }
  };

  bool built() const { return built_; }
  const Pairs& pairs(int t) const { return pairs_[t]; }
  int64_t pair_count() const;
  int64_t builds() const { return builds_; }
  double skin() const { return skin_; }
  // At the last build: the neighbour list's pairs and those touching.
  int64_t listed_at_build() const { return listed_; }
  int64_t touching_at_build() const { return touching_; }

 private:
  std::vector<Pairs> pairs_;
  std::vector<Vec4> build_positions_;
  std::array<double, 3> build_cell_{};
  double skin_ = 0;
  double max_radius_ = 0;
  bool built_ = false;
  int64_t builds_ = 0;
  int64_t listed_ = 0, touching_ = 0;
};

}  // namespace granasym::dem
