#include "dem/neighbor_list.h"

#include <gtest/gtest.h>

#include <vector>

namespace granasym::dem {
namespace {

// Four spheres of radius 0.5 mm in a row along x, 0.9 mm apart, in a 10 mm
// cell (scaled positions).
std::vector<Vec4> Row(double last_x = 0.37) {
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
  list.Build(Row(), cell, 0.1e-3, 1);
  ASSERT_EQ(list.pair_count(), 3u);  // neighbours only: 0-1, 1-2, 2-3
  ASSERT_EQ(list.rolling().size(), 3u);
  for (size_t p = 0; p < 3; ++p) {
    list.shear()[p] = {1.0 + p, 0, 0};
    list.rolling()[p] = {0, 0, 10.0 + p};
  }
  // Sphere 3 moves away: its pair leaves the list, the others keep their history.
  list.Build(Row(0.50), cell, 0.1e-3, 2);
  ASSERT_EQ(list.pair_count(), 2u);
  EXPECT_EQ(list.shear()[1].x, 2.0);
  EXPECT_EQ(list.rolling()[0].z, 10.0);
  EXPECT_EQ(list.rolling()[1].z, 11.0);
  // It comes back: a new pair starts without history.
  list.Build(Row(), cell, 0.1e-3, 1);
  ASSERT_EQ(list.pair_count(), 3u);
  EXPECT_EQ(list.rolling()[1].z, 11.0);
  EXPECT_EQ(list.rolling()[2].z, 0.0);
  EXPECT_EQ(list.shear()[2].x, 0.0);

  NeighborList restored;
  restored.set_track_rolling(true);
  restored.Restore(list.Save());
  EXPECT_EQ(restored.rolling()[1].z, 11.0);
  // A checkpoint without the rolling history cannot continue a scene with it.
  NeighborList::State incomplete = list.Save();
  incomplete.rolling.clear();
  EXPECT_THROW(restored.Restore(incomplete), std::exception);
}

TEST(NeighborList, KeepsNoRollingHistoryUnlessTracked) {
  NeighborList list;
  list.Build(Row(), {0.01, 0.01, 0.01}, 0.1e-3, 1);
  EXPECT_EQ(list.pair_count(), 3u);
  EXPECT_EQ(list.shear().size(), 3u);  // tracked by default
  EXPECT_TRUE(list.rolling().empty());
}

}  // namespace
}  // namespace granasym::dem
