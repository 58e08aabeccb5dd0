// The near list of dem/near_list.h against a brute-force selection of the
// neighbour list's pairs on random periodic arrangements of mixed spheres.
#include "dem/near_list.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "dem/minimum_image.h"
#include "dem/neighbor_list.h"

namespace granasym::dem {
namespace {

using Cell = std::array<double, 3>;

// Random spheres (overlaps allowed, so every gap occurs) filling about a
// half of the cell.
std::vector<Vec4> Arrangement(const Cell& cell, uint64_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0), radius(0.2e-3, 0.5e-3);
  std::vector<Vec4> s;
  double solid = 0;
  while (solid < 0.5 * cell[0] * cell[1] * cell[2]) {
    const double r = radius(random);
    s.push_back({unit(random), unit(random), unit(random), r});
    solid += 4.0 / 3.0 * M_PI * r * r * r;
  }
  return s;
}

double Gap(const std::vector<Vec4>& s, int i, int j, const Cell& cell) {
  return Norm(Branch(s[i], s[j], cell[0], cell[1], cell[2])) - s[i].w - s[j].w;
}

// The force pass takes the minimum image of whole Vec4s at once (a GCC
// vector of four doubles); each lane must be the scalar result, bit for bit,
// so that the pass's branch vectors are those of the scalar code.
TEST(MinimumImage, EachLaneOfAVectorIsTheScalarResultBitForBit) {
  using Lanes = double __attribute__((vector_size(32)));
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> separation(-1.5, 1.5);
  std::vector<double> deltas = {0.0,
                                -0.0,
                                0.5,
                                -0.5,
                                1.0,
                                -1.0,
                                1.5,
                                -1.5,
                                1e-300,
                                0.25,
                                0.999999,
                                std::nextafter(0.5, 1.0),
                                std::nextafter(0.5, 0.0),
                                std::nextafter(-0.5, -1.0)};
  for (int k = 0; k < 4000; ++k) deltas.push_back(separation(random));
  for (size_t k = 0; k + 4 <= deltas.size(); k += 4) {
    const Lanes delta = {deltas[k], deltas[k + 1], deltas[k + 2], deltas[k + 3]};
    const Lanes image = MinimumImage(delta);
    for (int lane = 0; lane < 4; ++lane) {
      const double scalar = MinimumImage(deltas[k + lane]);
      EXPECT_LE(std::abs(scalar), 0.5) << deltas[k + lane];
      EXPECT_EQ(std::memcmp(&scalar, &image[lane], sizeof scalar), 0)
          << "lane " << lane << " of " << deltas[k + lane] << ": " << image[lane] << " against "
          << scalar;
    }
  }
}

TEST(NearList, SelectsTheListedPairsWithinItsSkinInListOrderPerThread) {
  const Cell cell = {6e-3, 5e-3, 7e-3};
  const std::vector<Vec4> s = Arrangement(cell, 5);
  const double skin = 0.3 * 2 * 0.2e-3;
  NeighborList list;
  list.Build(s, cell, skin, 1);
  const int64_t n = static_cast<int64_t>(s.size());
  for (int threads : {1, 2, 3}) {
    for (double near_skin : {skin, skin / 4, skin / 64}) {
      SCOPED_TRACE(std::to_string(threads) + " threads, skin " + std::to_string(near_skin));
      NearList near;
      near.Build(list, s, cell, near_skin, threads, {});
      int64_t expected_total = 0, touching = 0;
      for (int t = 0; t < threads; ++t) {
        std::vector<int64_t> expected;
        for (int64_t p = list.offsets()[n * t / threads]; p < list.offsets()[n * (t + 1) / threads];
             ++p) {
          const double gap = Gap(s, list.owners()[p], list.neighbors()[p], cell);
          if (gap < near_skin) expected.push_back(p);
          touching += gap < 0;
        }
        const NearList::Pairs& pairs = near.pairs(t);
        ASSERT_EQ(pairs.size(), static_cast<int64_t>(expected.size()));
        for (size_t k = 0; k < expected.size(); ++k) {
          ASSERT_EQ(pairs.p[k], expected[k]);
          ASSERT_EQ(pairs.i[k], list.owners()[expected[k]]);
          ASSERT_EQ(pairs.j[k], list.neighbors()[expected[k]]);
        }
        expected_total += static_cast<int64_t>(expected.size());
      }
      EXPECT_EQ(near.pair_count(), expected_total);
      EXPECT_EQ(near.touching_at_build(), touching);
      EXPECT_EQ(near.listed_at_build(), static_cast<int64_t>(list.pair_count()));
      EXPECT_GT(touching, 50);
      EXPECT_GT(expected_total, touching);
      if (near_skin < skin) {
        EXPECT_LT(expected_total, static_cast<int64_t>(list.pair_count()));
      }
    }
  }
}

// A pair left out is not touching; one that held a history (touched at the
// last evaluation) forgets it, as the force pass would; the others keep it.
TEST(NearList, ALeftOutPairForgetsItsHistory) {
  const Cell cell = {6e-3, 6e-3, 6e-3};
  const std::vector<Vec4> s = Arrangement(cell, 9);
  const double skin = 0.6 * 0.2e-3;
  NeighborList list;
  list.set_track_rolling(true);
  list.Build(s, cell, skin, 1);
  const size_t pairs = list.pair_count();
  std::vector<uint8_t> loaded(pairs, 1);
  for (size_t p = 0; p < pairs; ++p) {
    list.shear()[p] = {1.0 + p, 2.0, 3.0};
    list.rolling()[p] = {4.0, 5.0 + p, 6.0};
  }
  NearList near;
  near.Build(list, s, cell, skin / 8, 2,
             {loaded.data(), list.shear().data(), list.rolling().data()});
  std::vector<bool> selected(pairs, false);
  for (int t = 0; t < 2; ++t) {
    for (int64_t k = 0; k < near.pairs(t).size(); ++k) selected[near.pairs(t).p[k]] = true;
  }
  int64_t forgotten = 0;
  for (size_t p = 0; p < pairs; ++p) {
    if (selected[p]) {
      EXPECT_EQ(loaded[p], 1);
      EXPECT_EQ(list.shear()[p].x, 1.0 + p);
      EXPECT_EQ(list.rolling()[p].y, 5.0 + p);
    } else {
      EXPECT_GE(Gap(s, list.owners()[p], list.neighbors()[p], cell), skin / 8);
      EXPECT_EQ(loaded[p], 0);
      EXPECT_EQ(list.shear()[p].x, 0.0);
      EXPECT_EQ(list.rolling()[p].y, 0.0);
      ++forgotten;
    }
  }
  EXPECT_GT(forgotten, 0);
}

// The criterion of the neighbour list with the near list's skin: rebuilt
// once two spheres may have closed it by their displacements or the strain.
TEST(NearList, NeedsRebuildOnceItsSkinMayBeUsedUp) {
  const Cell cell = {6e-3, 6e-3, 6e-3};
  const std::vector<Vec4> s = Arrangement(cell, 3);
  const double skin = 0.6 * 0.2e-3, near_skin = skin / 8;
  NeighborList list;
  list.Build(s, cell, skin, 1);
  NearList near;
  EXPECT_TRUE(near.NeedsRebuild(0.0, cell));  // not built
  near.Build(list, s, cell, near_skin, 1, {});
  EXPECT_FALSE(near.NeedsRebuild(0.0, cell));
  EXPECT_FALSE(near.NeedsRebuild(0.49 * near_skin, cell));
  EXPECT_TRUE(near.NeedsRebuild(0.5 * near_skin, cell));
  // Strain: ε (2 r_max + s) reaching s.
  const double epsilon = near_skin / (2 * list.max_radius() + near_skin);
  Cell strained = cell;
  strained[1] *= 1 - 0.99 * epsilon;
  EXPECT_FALSE(near.NeedsRebuild(0.0, strained));
  strained[1] = cell[1] * (1 - 1.01 * epsilon);
  EXPECT_TRUE(near.NeedsRebuild(0.0, strained));
  EXPECT_NEAR(near.SkinUsed(0.1 * near_skin, cell), 0.2 * near_skin, 1e-20);
  // The displacement measured against the build's positions.
  std::vector<Vec4> moved = s;
  moved[7].y += 0.3 * near_skin / cell[1];
  EXPECT_NEAR(near.MaxDisplacement(moved, cell, 2), 0.3 * near_skin, 1e-6 * near_skin);
  near.Clear();
  EXPECT_TRUE(near.NeedsRebuild(0.0, cell));
}

TEST(NearList, CheapestSkinBalancesTheWalkedPairsAgainstTheBuilds) {
  // s* = sqrt(overhead · c · s / (near − touching)).
  const double skin = 1e-5, overhead = NearList::BuildOverhead(40000, 10000, 3);
  EXPECT_DOUBLE_EQ(overhead, NearList::kBuildCost * 40000 + NearList::kMeasureCost * 30000);
  const double expected = std::sqrt(overhead * 2e-7 * skin / 2000);
  EXPECT_GT(expected, 0.5 * skin);
  EXPECT_LT(expected, 2 * skin);
  EXPECT_DOUBLE_EQ(NearList::CheapestSkin(skin, overhead, 12000, 10000, 2e-7, 1e-9, 1e-3),
                   expected);
  // At most a factor 2 per build, and within the bounds.
  EXPECT_DOUBLE_EQ(NearList::CheapestSkin(skin, overhead, 12000, 10000, 1.0, 1e-9, 1e-3), 2 * skin);
  EXPECT_DOUBLE_EQ(NearList::CheapestSkin(skin, overhead, 12000, 10000, 1e-20, 1e-9, 1e-3),
                   0.5 * skin);
  EXPECT_DOUBLE_EQ(NearList::CheapestSkin(skin, overhead, 12000, 10000, 1.0, 1e-9, 1.5e-5), 1.5e-5);
  EXPECT_DOUBLE_EQ(NearList::CheapestSkin(skin, overhead, 12000, 10000, 1e-20, 8e-6, 1e-3), 8e-6);
  // Nothing moved: narrower; no pair between touching and the skin: wider.
  EXPECT_DOUBLE_EQ(NearList::CheapestSkin(skin, overhead, 12000, 10000, 0.0, 1e-9, 1e-3),
                   0.5 * skin);
  EXPECT_DOUBLE_EQ(NearList::CheapestSkin(skin, overhead, 10000, 10000, 1e-8, 1e-9, 1e-3),
                   2 * skin);
}

}  // namespace
}  // namespace granasym::dem
