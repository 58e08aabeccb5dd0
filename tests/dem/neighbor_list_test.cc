// The Verlet list of dem/neighbor_list.h against a brute-force O(N²) pair
// search on random periodic arrangements of mixed spheres, under the engine's
// diagonal cell deformation and small non-affine moves.
#include "dem/neighbor_list.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "common/error.h"
#include "common/state_measures.h"

namespace granasym::dem {
namespace {

using Cell = std::array<double, 3>;

// Half list in the same CSR layout as NeighborList.
struct PairList {
  std::vector<int64_t> offsets;
  std::vector<int32_t> neighbors;
};

Vec3 MinimumImage(const Vec4& a, const Vec4& b, const Cell& cell) {
  double ds[3] = {b.x - a.x, b.y - a.y, b.z - a.z};
  for (int d = 0; d < 3; ++d) ds[d] = cell[d] * (ds[d] - std::round(ds[d]));
  return {ds[0], ds[1], ds[2]};
}

// Surface gap of the minimum image of the pair (m); negative when overlapping.
double Gap(const std::vector<Vec4>& s, int i, int j, const Cell& cell) {
  return Norm(MinimumImage(s[i], s[j], cell)) - s[i].w - s[j].w;
}

// Every pair i < j whose minimum-image centre distance is below r_i + r_j + skin.
PairList BruteForcePairs(const std::vector<Vec4>& s, const Cell& cell, double skin) {
  const int n = static_cast<int>(s.size());
  PairList list;
  list.offsets.push_back(0);
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const Vec3 d = MinimumImage(s[i], s[j], cell);
      const double cut = s[i].w + s[j].w + skin;
      if (Dot(d, d) < cut * cut) list.neighbors.push_back(j);
    }
    list.offsets.push_back(static_cast<int64_t>(list.neighbors.size()));
  }
  return list;
}

bool Listed(const NeighborList& list, int i, int j) {
  const auto begin = list.neighbors().begin() + list.offsets()[i];
  const auto end = list.neighbors().begin() + list.offsets()[i + 1];
  return std::binary_search(begin, end, j);
}

double MaxRadius(const std::vector<Vec4>& s) {
  double r = 0;
  for (const Vec4& p : s) r = std::max(r, p.w);
  return r;
}

// Uniformly random (overlaps allowed, so every gap occurs) spheres of radii
// in [r_min, r_max], filling `solid_fraction` of the cell, plus one sphere
// near each of the eight corners so that pairs cross every face, edge and
// corner of the cell.
std::vector<Vec4> RandomArrangement(const Cell& cell, double r_min, double r_max,
                                    double solid_fraction, std::mt19937_64& random) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> radius(r_min, r_max);
  std::vector<Vec4> s;
  for (int corner = 0; corner < 8; ++corner) {
    const double near_low = 0.02, near_high = 0.97;
    s.push_back({corner & 1 ? near_high : near_low, corner & 2 ? near_high : near_low,
                 corner & 4 ? near_high : near_low, r_max});
  }
  const double volume = cell[0] * cell[1] * cell[2];
  double solid = 8 * 4.0 / 3.0 * kPi * r_max * r_max * r_max;
  while (solid < solid_fraction * volume) {
    const double r = radius(random);
    s.push_back({unit(random), unit(random), unit(random), r});
    solid += 4.0 / 3.0 * kPi * r * r * r;
  }
  std::shuffle(s.begin(), s.end(), random);
  return s;
}

// The 13 image directions (26 up to sign) across which the listed pairs reach.
std::set<std::array<int, 3>> ImageDirections(const std::vector<Vec4>& s, const PairList& list) {
  std::set<std::array<int, 3>> directions;
  auto wrap = [](double x) { return x - std::floor(x); };
  for (size_t i = 0; i + 1 < list.offsets.size(); ++i) {
    for (int64_t p = list.offsets[i]; p < list.offsets[i + 1]; ++p) {
      const Vec4& a = s[i];
      const Vec4& b = s[list.neighbors[p]];
      std::array<int, 3> shift = {static_cast<int>(std::round(wrap(b.x) - wrap(a.x))),
                                  static_cast<int>(std::round(wrap(b.y) - wrap(a.y))),
                                  static_cast<int>(std::round(wrap(b.z) - wrap(a.z)))};
      // Identify a direction with its opposite: first non-zero component positive.
      for (int d = 0; d < 3; ++d) {
        if (shift[d] != 0) {
          if (shift[d] < 0) {
            for (int& c : shift) c = -c;
          }
          break;
        }
      }
      if (shift != std::array<int, 3>{0, 0, 0}) directions.insert(shift);
    }
  }
  return directions;
}

void ExpectEqualsBruteForce(const NeighborList& list, const std::vector<Vec4>& s, const Cell& cell,
                            double skin, const std::string& when) {
  const PairList expected = BruteForcePairs(s, cell, skin);
  ASSERT_EQ(list.offsets(), expected.offsets) << when;
  ASSERT_EQ(list.neighbors(), expected.neighbors) << when;
  ASSERT_EQ(list.pair_count(), expected.neighbors.size()) << when;
  ASSERT_EQ(list.owners().size(), list.pair_count()) << when;
  for (size_t i = 0; i + 1 < expected.offsets.size(); ++i) {
    for (int64_t p = expected.offsets[i]; p < expected.offsets[i + 1]; ++p) {
      ASSERT_EQ(list.owners()[p], static_cast<int32_t>(i)) << when << ", pair " << p;
    }
  }
}

// Runs one deformation history of `steps` increments from a random
// arrangement in `cell`: the cell side `compressed` shrinks and `extended`
// grows by `strain_per_step` (relative), every sphere moves by a non-affine
// displacement of up to `move` (m). Checks the list at every
// increment and counts what it checked in `stats`.
struct HistoryStats {
  int64_t builds = 0;
  int64_t carried_pairs = 0;    // pairs whose shear history crossed a rebuild
  int64_t new_pairs = 0;        // pairs that appeared at a rebuild
  int64_t touching_checks = 0;  // touching pairs checked against a kept list
};

void RunDeformationHistory(Cell cell, int compressed, int extended, int steps, int threads,
                           uint64_t seed, HistoryStats* stats) {
  std::mt19937_64 random(seed);
  const double r_min = 0.2e-3, r_max = 0.5e-3;
  const double skin = 0.3 * 2.0 * r_min;  // the engine's default skin_fraction
  std::vector<Vec4> s = RandomArrangement(cell, r_min, r_max, 0.45, random);
  const int n = static_cast<int>(s.size());
  const double max_radius = MaxRadius(s);
  const double strain_per_step = 1e-3;
  const double move = skin / 25.0;

  NeighborList list;
  list.Build(s, cell, skin, threads);
  ExpectEqualsBruteForce(list, s, cell, skin, "first build");
  EXPECT_EQ(ImageDirections(s, BruteForcePairs(s, cell, skin)).size(), 13u)
      << "the arrangement must have pairs across every face, edge and corner";
  Cell build_cell = cell;

  // Each sphere drifts along its own random direction, plus a random jitter:
  // spheres drifting towards each other close their gap at twice the largest
  // displacement, the worst case the criterion allows for.
  std::normal_distribution<double> normal(0.0, 1.0);
  auto random_direction = [&] {
    const Vec3 direction{normal(random), normal(random), normal(random)};
    return (1.0 / Norm(direction)) * direction;
  };
  std::vector<Vec3> drift(n);
  for (Vec3& d : drift) d = random_direction();
  for (int step = 1; step <= steps; ++step) {
    // Affine part: the scaled positions stay, the cell sides change.
    cell[compressed] *= 1.0 - strain_per_step;
    cell[extended] *= 1.0 + strain_per_step;
    // Non-affine part: a displacement (m) in the current metric; positions
    // are deliberately not wrapped into [0, 1) between builds.
    for (int i = 0; i < n; ++i) {
      const Vec3 move_i = move * (0.8 * drift[i] + 0.2 * random_direction());
      s[i].x += move_i.x / cell[0];
      s[i].y += move_i.y / cell[1];
      s[i].z += move_i.z / cell[2];
    }
    const std::string when = "step " + std::to_string(step);
    const double max_displacement = list.MaxDisplacement(s, cell, threads);
    if (!list.NeedsRebuild(max_displacement, cell)) {
      // The kept list must hold every pair in contact. More precisely, the
      // criterion guarantees every pair whose gap is below
      //   skin − 2 max|δx| − ε (2 r_max + skin).
      double strain = 0;
      for (int d = 0; d < 3; ++d) strain = std::max(strain, std::abs(cell[d] / build_cell[d] - 1));
      const double guaranteed_gap =
          skin - 2.0 * max_displacement - strain * (2.0 * max_radius + skin);
      ASSERT_GT(guaranteed_gap, 0.0) << when;
      for (int i = 0; i < n; ++i) {
        for (int j = i + 1; j < n; ++j) {
          const double gap = Gap(s, i, j, cell);
          if (gap < 0) {
            ++stats->touching_checks;
            ASSERT_TRUE(Listed(list, i, j))
                << when << ": touching pair " << i << "-" << j << " (gap " << gap
                << " m) is missing from a list that claims to be valid";
          }
          if (gap < guaranteed_gap * (1 - 1e-9)) {
            ASSERT_TRUE(Listed(list, i, j))
                << when << ": pair " << i << "-" << j << " with gap " << gap
                << " m below the guaranteed " << guaranteed_gap << " m is missing";
          }
        }
      }
      continue;
    }
    // Label the shear history of each pair with its owner, neighbour and build.
    const PairList before{list.offsets(), list.neighbors()};
    const double label_build = static_cast<double>(list.builds());
    for (size_t p = 0; p < list.pair_count(); ++p) {
      list.shear()[p] = {double(list.owners()[p]), double(list.neighbors()[p]), label_build};
    }
    // Alternate between wrapped positions (as the engine passes them) and
    // unwrapped ones (the list accepts any real scaled position).
    if (list.builds() % 2 == 0) {
      for (Vec4& p : s) {
        p.x -= std::floor(p.x);
        p.y -= std::floor(p.y);
        p.z -= std::floor(p.z);
      }
    }
    list.Build(s, cell, skin, threads);
    build_cell = cell;
    ExpectEqualsBruteForce(list, s, cell, skin, when + " rebuild");
    EXPECT_EQ(list.MaxDisplacement(s, cell, threads), 0.0) << when;
    EXPECT_FALSE(list.NeedsRebuild(0.0, cell)) << when;
    for (int i = 0; i < n; ++i) {
      for (int64_t p = list.offsets()[i]; p < list.offsets()[i + 1]; ++p) {
        const int j = list.neighbors()[p];
        const auto begin = before.neighbors.begin() + before.offsets[i];
        const auto end = before.neighbors.begin() + before.offsets[i + 1];
        const Vec3 shear = list.shear()[p];
        if (std::binary_search(begin, end, j)) {
          ++stats->carried_pairs;
          ASSERT_EQ(shear.x, double(i)) << when;
          ASSERT_EQ(shear.y, double(j)) << when;
          ASSERT_EQ(shear.z, label_build) << when;
        } else {
          ++stats->new_pairs;
          ASSERT_EQ(shear.x, 0.0) << when << ": new pair " << i << "-" << j;
          ASSERT_EQ(shear.y, 0.0) << when;
          ASSERT_EQ(shear.z, 0.0) << when;
        }
      }
    }
  }
  stats->builds = list.builds();
}

TEST(NeighborList, MatchesBruteForceUnderCompressionAndExtensionWithRandomMoves) {
  // 5.5 mm cube: four bins of side >= reach along each axis.
  HistoryStats stats;
  RunDeformationHistory({5.5e-3, 5.5e-3, 5.5e-3}, /*compressed=*/0, /*extended=*/1,
                        /*steps=*/250, /*threads=*/3, /*seed=*/11, &stats);
  // The history must exercise what it checks: several rebuilds, carried and
  // new pairs, kept lists with touching pairs.
  EXPECT_GE(stats.builds, 5);
  EXPECT_GT(stats.carried_pairs, 0);
  EXPECT_GT(stats.new_pairs, 0);
  EXPECT_GT(stats.touching_checks, 1000);
}

TEST(NeighborList, MatchesBruteForceInAThinCellWithASingleBinAcrossOneAxis) {
  // The z side holds fewer than three bins of the reach (1.12 mm): one bin
  // spans it; z is compressed, x extended.
  HistoryStats stats;
  RunDeformationHistory({6.0e-3, 6.0e-3, 3.0e-3}, /*compressed=*/2, /*extended=*/0,
                        /*steps=*/250, /*threads=*/2, /*seed=*/5, &stats);
  EXPECT_GE(stats.builds, 4);
  EXPECT_GT(stats.new_pairs, 0);
  EXPECT_GT(stats.touching_checks, 100);
}

TEST(NeighborList, ThreadCountDoesNotChangeTheList) {
  std::mt19937_64 random(7);
  const Cell cell = {5e-3, 4.5e-3, 6e-3};
  const std::vector<Vec4> s = RandomArrangement(cell, 0.2e-3, 0.5e-3, 0.3, random);
  NeighborList serial, parallel;
  serial.Build(s, cell, 0.12e-3, 1);
  parallel.Build(s, cell, 0.12e-3, 4);
  EXPECT_EQ(serial.offsets(), parallel.offsets());
  EXPECT_EQ(serial.neighbors(), parallel.neighbors());
  EXPECT_EQ(serial.owners(), parallel.owners());
}

TEST(NeighborList, PositionsShiftedByWholeCellsGiveTheSameList) {
  std::mt19937_64 random(3);
  const Cell cell = {5e-3, 5e-3, 5e-3};
  const std::vector<Vec4> s = RandomArrangement(cell, 0.2e-3, 0.5e-3, 0.3, random);
  std::vector<Vec4> shifted = s;
  for (size_t i = 0; i < shifted.size(); ++i) {
    shifted[i].x += static_cast<double>(static_cast<int>(i % 5) - 2);
    shifted[i].y -= static_cast<double>(i % 3);
    shifted[i].z += static_cast<double>(i % 2) * 3.0;
  }
  NeighborList wrapped, unwrapped;
  wrapped.Build(s, cell, 0.12e-3, 2);
  unwrapped.Build(shifted, cell, 0.12e-3, 2);
  EXPECT_EQ(wrapped.offsets(), unwrapped.offsets());
  EXPECT_EQ(wrapped.neighbors(), unwrapped.neighbors());
}

TEST(NeighborList, ShearHistoryIsCarriedForKeptPairsAndZeroForNewOnes) {
  // Three spheres on the x axis: 0-1 touch, 1-2 are beyond the skin. Moving
  // sphere 2 towards 1 and sphere 0 away keeps nothing but adds 1-2.
  const Cell cell = {10e-3, 10e-3, 10e-3};
  const double r = 0.5e-3, skin = 0.1e-3;
  std::vector<Vec4> s = {{0.30, 0.5, 0.5, r}, {0.40, 0.5, 0.5, r}, {0.53, 0.5, 0.5, r}};
  NeighborList list;
  list.Build(s, cell, skin, 1);
  ASSERT_EQ(list.neighbors(), (std::vector<int32_t>{1}));
  list.shear()[0] = {1.5, -2.5, 3.5};
  // Pair 0-1 stays; pair 1-2 becomes listed (gap 0.3 mm → 0.05 mm).
  s[2].x = 0.505;
  list.Build(s, cell, skin, 1);
  ASSERT_EQ(list.offsets(), (std::vector<int64_t>{0, 1, 2, 2}));
  ASSERT_EQ(list.neighbors(), (std::vector<int32_t>{1, 2}));
  EXPECT_EQ(list.shear()[0].x, 1.5);
  EXPECT_EQ(list.shear()[0].y, -2.5);
  EXPECT_EQ(list.shear()[0].z, 3.5);
  EXPECT_EQ(list.shear()[1].x, 0.0);
  EXPECT_EQ(list.shear()[1].y, 0.0);
  EXPECT_EQ(list.shear()[1].z, 0.0);
  // A pair that leaves and comes back starts afresh.
  list.shear()[1] = {7.0, 7.0, 7.0};
  s[0].x = 0.2;
  list.Build(s, cell, skin, 1);
  ASSERT_EQ(list.neighbors(), (std::vector<int32_t>{2}));
  s[0].x = 0.30;
  list.Build(s, cell, skin, 1);
  ASSERT_EQ(list.neighbors(), (std::vector<int32_t>{1, 2}));
  EXPECT_EQ(list.shear()[0].x, 0.0);
  EXPECT_EQ(list.shear()[1].x, 7.0);
  EXPECT_EQ(list.builds(), 4);
}

TEST(NeighborList, WithoutShearTrackingKeepsNoHistory) {
  const Cell cell = {10e-3, 10e-3, 10e-3};
  const std::vector<Vec4> s = {{0.30, 0.5, 0.5, 0.5e-3}, {0.40, 0.5, 0.5, 0.5e-3}};
  NeighborList list;
  list.set_track_shear(false);
  list.Build(s, cell, 0.1e-3, 1);
  EXPECT_EQ(list.pair_count(), 1u);
  EXPECT_TRUE(list.shear().empty());
}

TEST(NeighborList, SaveAndRestoreRoundTripTheCompleteState) {
  std::mt19937_64 random(19);
  Cell cell = {5e-3, 5e-3, 5e-3};
  std::vector<Vec4> s = RandomArrangement(cell, 0.2e-3, 0.5e-3, 0.3, random);
  const double skin = 0.12e-3;
  NeighborList original;
  original.Build(s, cell, skin, 2);
  original.Build(s, cell, skin, 2);  // builds() == 2
  for (size_t p = 0; p < original.pair_count(); ++p) {
    original.shear()[p] = {double(p), -double(p), 0.5};
  }
  const NeighborList::State state = original.Save();
  NeighborList restored;
  // A list with other content before the restore: nothing of it may remain.
  std::vector<Vec4> other = {{0.1, 0.1, 0.1, 0.4e-3}, {0.15, 0.1, 0.1, 0.4e-3}};
  restored.Build(other, cell, 0.2e-3, 1);
  restored.Restore(state);

  EXPECT_EQ(restored.offsets(), original.offsets());
  EXPECT_EQ(restored.neighbors(), original.neighbors());
  EXPECT_EQ(restored.owners(), original.owners());
  ASSERT_EQ(restored.shear().size(), original.shear().size());
  for (size_t p = 0; p < original.pair_count(); ++p) {
    EXPECT_EQ(restored.shear()[p].x, original.shear()[p].x);
    EXPECT_EQ(restored.shear()[p].y, original.shear()[p].y);
    EXPECT_EQ(restored.shear()[p].z, original.shear()[p].z);
  }
  EXPECT_EQ(restored.builds(), 2);
  EXPECT_EQ(restored.skin(), skin);
  EXPECT_EQ(restored.MetricFactor(), original.MetricFactor());

  // The restored list continues exactly as the original: same displacement,
  // same criterion, same rebuild with the same carried history.
  cell[0] *= 0.99;
  cell[2] *= 1.01;
  std::normal_distribution<double> normal(0.0, 0.02e-3);
  for (Vec4& p : s) {
    p.x += normal(random) / cell[0];
    p.y += normal(random) / cell[1];
    p.z += normal(random) / cell[2];
  }
  const double displacement = original.MaxDisplacement(s, cell, 1);
  EXPECT_EQ(restored.MaxDisplacement(s, cell, 1), displacement);
  for (double d : {0.0, 0.25 * skin, 0.5 * skin}) {
    EXPECT_EQ(restored.NeedsRebuild(d, cell), original.NeedsRebuild(d, cell)) << d;
  }
  original.Build(s, cell, skin, 2);
  restored.Build(s, cell, skin, 2);
  EXPECT_EQ(restored.neighbors(), original.neighbors());
  ASSERT_EQ(restored.shear().size(), original.shear().size());
  for (size_t p = 0; p < original.pair_count(); ++p) {
    EXPECT_EQ(restored.shear()[p].x, original.shear()[p].x) << p;
  }
  EXPECT_EQ(restored.builds(), 3);
}

TEST(NeighborList, MaxDisplacementIsTheLargestNonAffineMoveInTheCurrentMetric) {
  std::mt19937_64 random(23);
  const Cell build_cell = {5e-3, 5e-3, 5e-3};
  const std::vector<Vec4> built = RandomArrangement(build_cell, 0.2e-3, 0.5e-3, 0.3, random);
  NeighborList list;
  list.Build(built, build_cell, 0.12e-3, 1);

  // A pure affine deformation moves nothing.
  const Cell cell = {4.8e-3, 5.3e-3, 5.05e-3};
  EXPECT_EQ(list.MaxDisplacement(built, cell, 3), 0.0);

  std::vector<Vec4> s = built;
  std::uniform_real_distribution<double> offset(-1e-2, 1e-2);
  for (Vec4& p : s) {
    p.x += offset(random);
    p.y += offset(random);
    p.z += offset(random);
  }
  double expected = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    const Vec3 move{cell[0] * (s[i].x - built[i].x), cell[1] * (s[i].y - built[i].y),
                    cell[2] * (s[i].z - built[i].z)};
    expected = std::max(expected, Norm(move));
  }
  EXPECT_NEAR(list.MaxDisplacement(s, cell, 1), expected, 1e-15 * expected);
  EXPECT_NEAR(list.MaxDisplacement(s, cell, 3), expected, 1e-15 * expected);
  // One sphere moved far dominates, measured with the current (not the build) cell.
  s[17].y = built[17].y + 0.1;
  EXPECT_NEAR(list.MaxDisplacement(s, cell, 2),
              std::hypot(cell[0] * (s[17].x - built[17].x), cell[1] * 0.1,
                         cell[2] * (s[17].z - built[17].z)),
              1e-15);
}

TEST(NeighborList, RebuildCriterionBoundaries) {
  const Cell cell = {10e-3, 10e-3, 10e-3};
  const double r = 0.5e-3, skin = 0.2e-3;
  const std::vector<Vec4> s = {{0.3, 0.5, 0.5, r}, {0.4, 0.5, 0.5, 0.25e-3}};
  NeighborList list;
  EXPECT_TRUE(list.NeedsRebuild(0.0, cell)) << "an unbuilt list must be built";
  list.Build(s, cell, skin, 1);
  EXPECT_FALSE(list.NeedsRebuild(0.0, cell));
  // 2 max|δx| + ε (2 r_max + skin) < skin keeps the list.
  EXPECT_FALSE(list.NeedsRebuild(0.49 * skin, cell));
  EXPECT_TRUE(list.NeedsRebuild(0.5 * skin, cell));
  const double reach = 2 * r + skin;
  const double strain = 0.5 * skin / reach;  // uses half the skin
  Cell stretched = cell;
  stretched[1] *= 1 + strain;
  EXPECT_FALSE(list.NeedsRebuild(0.24 * skin, stretched));
  EXPECT_TRUE(list.NeedsRebuild(0.26 * skin, stretched));
  Cell compressed = cell;
  compressed[2] *= 1 - 1.01 * skin / reach;
  EXPECT_TRUE(list.NeedsRebuild(0.0, compressed));
  // The metric factor bounds the growth of a displacement over the cell
  // changes the criterion allows: (1 + ε*) / (1 − ε*), ε* = skin / reach.
  EXPECT_NEAR(list.MetricFactor(), (1 + skin / reach) / (1 - skin / reach), 1e-15);
}

TEST(NeighborList, CellSmallerThanTwiceTheReachIsAnError) {
  const double r = 0.5e-3, skin = 0.1e-3;
  const double reach = 2 * r + skin;
  const std::vector<Vec4> s = {{0.2, 0.5, 0.5, r}, {0.6, 0.5, 0.5, 0.3e-3}};
  NeighborList list;
  Cell cell = {5e-3, 5e-3, 5e-3};
  list.Build(s, cell, skin, 1);
  const std::vector<int64_t> offsets = list.offsets();
  // Compress y as the engine does until the cell is exactly twice the reach.
  cell[1] = 2 * reach;
  try {
    list.Build(s, cell, skin, 1);
    FAIL() << "a cell side of twice the reach must be refused";
  } catch (const RuntimeError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("smaller than twice the interaction reach"), std::string::npos)
        << message;
    EXPECT_NE(message.find("2.2"), std::string::npos) << "the side in mm: " << message;
    EXPECT_NE(message.find("1.1"), std::string::npos) << "the reach in mm: " << message;
  }
  // The failed build leaves the list as it was.
  EXPECT_EQ(list.offsets(), offsets);
  EXPECT_EQ(list.builds(), 1);
  cell[1] = 2 * reach * (1 + 1e-9);
  EXPECT_NO_THROW(list.Build(s, cell, skin, 1));
  cell[1] = std::nan("");
  EXPECT_THROW(list.Build(s, cell, skin, 1), RuntimeError);
}

// Four spheres of radius 0.5 mm in a row along x, 0.9 mm apart, in a 10 mm
// cell (scaled positions).
std::vector<Vec4> FourInARow(double last_x = 0.37) {
  return {{0.10, 0.5, 0.5, 0.5e-3},
          {0.19, 0.5, 0.5, 0.5e-3},
          {0.28, 0.5, 0.5, 0.5e-3},
          {last_x, 0.5, 0.5, 0.5e-3}};
}

TEST(NeighborList, ShearAndRollingHistoriesAreCarriedAcrossRebuilds) {
  const std::array<double, 3> cell = {0.01, 0.01, 0.01};
  NeighborList list;
  list.set_track_shear(true);
  list.set_track_rolling(true);
  list.Build(FourInARow(), cell, 0.1e-3, 1);
  ASSERT_EQ(list.pair_count(), 3u);  // neighbours only: 0-1, 1-2, 2-3
  ASSERT_EQ(list.rolling().size(), 3u);
  for (size_t p = 0; p < 3; ++p) {
    list.shear()[p] = {1.0 + p, 0, 0};
    list.rolling()[p] = {0, 0, 10.0 + p};
  }
  // Sphere 3 moves away: its pair leaves the list, the others keep their history.
  list.Build(FourInARow(0.50), cell, 0.1e-3, 2);
  ASSERT_EQ(list.pair_count(), 2u);
  EXPECT_EQ(list.shear()[1].x, 2.0);
  EXPECT_EQ(list.rolling()[0].z, 10.0);
  EXPECT_EQ(list.rolling()[1].z, 11.0);
  // It comes back: a new pair starts without history.
  list.Build(FourInARow(), cell, 0.1e-3, 1);
  ASSERT_EQ(list.pair_count(), 3u);
  EXPECT_EQ(list.rolling()[1].z, 11.0);
  EXPECT_EQ(list.rolling()[2].z, 0.0);
  EXPECT_EQ(list.shear()[2].x, 0.0);

  NeighborList restored;
  restored.set_track_rolling(true);
  restored.Restore(list.Save());
  EXPECT_EQ(restored.rolling()[1].z, 11.0);
  // A state saved without rolling resistance (a fork that adds it) starts
  // every pair from zero; a history of the wrong length is a broken state.
  NeighborList::State without = list.Save();
  without.rolling.clear();
  restored.Restore(without);
  ASSERT_EQ(restored.rolling().size(), 3u);
  EXPECT_EQ(restored.rolling()[1].z, 0.0);
  NeighborList::State broken = list.Save();
  broken.rolling.pop_back();
  EXPECT_THROW(restored.Restore(broken), InvariantError);
  // A list that does not keep a history drops the saved one.
  NeighborList frictionless;
  frictionless.set_track_shear(false);
  frictionless.Restore(list.Save());
  EXPECT_TRUE(frictionless.shear().empty());
  EXPECT_TRUE(frictionless.rolling().empty());
}

TEST(NeighborList, KeepsNoRollingHistoryUnlessTracked) {
  NeighborList list;
  list.Build(FourInARow(), {0.01, 0.01, 0.01}, 0.1e-3, 1);
  EXPECT_EQ(list.pair_count(), 3u);
  EXPECT_EQ(list.shear().size(), 3u);  // tracked by default
  EXPECT_TRUE(list.rolling().empty());
}

}  // namespace
}  // namespace granasym::dem
