// The odometry's voxel map of planes: planes against hand-made clouds, and keyframes that come and
// go leaving the map as if they had never been there.

#include "slam/sgraph/plane_voxel_map.hpp"

#include <gtest/gtest.h>

#include "slam/sgraph/voxel_index.hpp"
#include "slam/sgraph/voxel_key.hpp"

namespace isg::slam {
namespace {

// A wall x = 2.1 (in M) sampled every 5 cm over y ∈ [0, 1), z ∈ [0, 1).
std::vector<Eigen::Vector3f> voxelWallAt(float x) {
  std::vector<Eigen::Vector3f> out;
  for (int i = 0; i < 20; ++i) {
    for (int k = 0; k < 20; ++k) out.emplace_back(x, 0.05f * i + 0.025f, 0.05f * k + 0.025f);
  }
  return out;
}

TEST(VoxelIndex, FindsWhatWasInsertedAcrossGrowth) {
  VoxelIndex index(4);
  for (int i = 0; i < 5000; ++i) EXPECT_EQ(index.insert(std::uint64_t(i) * 7919u, i), i);
  EXPECT_EQ(index.size(), 5000u);
  // A key inserted again keeps its first index.
  EXPECT_EQ(index.insert(7919u * 10u, 99), 10);
  for (int i = 0; i < 5000; ++i) ASSERT_EQ(index.find(std::uint64_t(i) * 7919u), i);
  EXPECT_EQ(index.find(3), -1);
  index.clear(1);
  EXPECT_EQ(index.find(7919u), -1);
  EXPECT_EQ(index.size(), 0u);
}

TEST(VoxelKey, ACellsKeyGivesTheCellBackAndAPointsKeyIsItsCells) {
  // Cells at both ends of the ±2^20 range, the origin's neighbours and arbitrary ones.
  const std::vector<Eigen::Vector3i> cells = {{0, 0, 0},
                                              {-1, -1, -1},
                                              {1, -1, 0},
                                              {(1 << 20) - 1, -(1 << 20), 7},
                                              {-(1 << 20), (1 << 20) - 1, -12345},
                                              {4021, -77, 3}};
  for (const auto& cell : cells) {
    EXPECT_EQ(voxelCellOfKey(voxelKeyOfCell(cell)), cell) << cell.transpose();
  }
  // A point 2.25 m, −0.05 m, 0.4 m at 0.5 m voxels is in cell (4, −1, 0).
  const Eigen::Vector3d p(2.25, -0.05, 0.4);
  EXPECT_EQ(voxelKey(p, 0.5), voxelKeyOfCell(Eigen::Vector3i(4, -1, 0)));
  // Keys sort x first: a cell one further in x has a larger key than any with a smaller x.
  EXPECT_LT(voxelKeyOfCell({3, 900, 900}), voxelKeyOfCell({4, -900, -900}));
}

TEST(PlaneVoxelMap, AWallsVoxelsHoldItsPlane) {
  PlaneVoxelMap map;  // 0.5 m voxels
  map.add(map.contributionOf(voxelWallAt(2.1f), Eigen::Isometry3d::Identity()));
  // 20 × 20 points over 1 m × 1 m: four voxels of 10 × 10 (x = 2.1 lies in the cells 2.0–2.5).
  EXPECT_EQ(map.size(), 4u);
  // A point 7 cm in front of the wall: its own voxel's plane, 7 cm along the normal.
  const PlaneVoxelMap::Match near = map.match({2.17, 0.3, 0.3}, 0.25);
  ASSERT_NE(near.voxel, nullptr);
  EXPECT_TRUE(near.occupied);
  EXPECT_NEAR(std::abs(near.voxel->normal.x()), 1.0, 1e-9);
  EXPECT_NEAR(std::abs(near.residual), 0.07, 1e-6);
  EXPECT_NEAR(near.voxel->mean.x(), 2.1, 1e-6);
  EXPECT_NEAR(near.voxel->mean.y(), 0.25, 1e-6);  // the mean of 0.025 … 0.475
  // 1.95 m lies in the neighbouring (empty) cell 1.5–2.0: the wall's plane comes from the next.
  const PlaneVoxelMap::Match across = map.match({1.95, 0.3, 0.3}, 0.25);
  ASSERT_NE(across.voxel, nullptr);
  EXPECT_FALSE(across.occupied);
  EXPECT_NEAR(std::abs(across.residual), 0.15, 1e-6);
  // Beyond the tolerance: none.
  EXPECT_EQ(map.match({1.95, 0.3, 0.3}, 0.1).voxel, nullptr);
}

TEST(PlaneVoxelMap, AKeyframeTakenBackLeavesTheMapAsBefore) {
  PlaneVoxelMap map;
  const auto wall = map.contributionOf(voxelWallAt(2.1f), Eigen::Isometry3d::Identity());
  // The same wall seen from elsewhere 4 cm further: both together, a 4 cm thick slab.
  Eigen::Isometry3d moved = Eigen::Isometry3d::Identity();
  moved.translation().x() = 0.04;
  const auto later = map.contributionOf(voxelWallAt(2.1f), moved);
  map.add(wall);
  map.add(later);
  EXPECT_NEAR(map.match({2.3, 0.3, 0.3}, 0.25).voxel->mean.x(), 2.12, 1e-6);
  map.remove(wall);
  const PlaneVoxelMap::Match match = map.match({2.3, 0.3, 0.3}, 0.25);
  ASSERT_NE(match.voxel, nullptr);
  EXPECT_NEAR(match.voxel->mean.x(), 2.14, 1e-6);  // 2.1f + 0.04
  // As if the first had never been there, to the rounding of the sums.
  PlaneVoxelMap fresh;
  fresh.add(later);
  const PlaneVoxelMap::Match expected = fresh.match({2.3, 0.3, 0.3}, 0.25);
  EXPECT_NEAR(match.voxel->mean.x(), expected.voxel->mean.x(), 1e-12);
  EXPECT_NEAR(match.residual, expected.residual, 1e-12);
  EXPECT_NEAR(match.voxel->normal.dot(expected.voxel->normal), 1.0, 1e-12);
  map.remove(later);
  EXPECT_TRUE(map.empty());
  EXPECT_EQ(map.match({2.3, 0.3, 0.3}, 0.25).voxel, nullptr);
}

TEST(PlaneVoxelMap, ALineOfPointsIsNoPlane) {
  // One ring's points along a wall: a line, whose "normal" is any direction across it.
  std::vector<Eigen::Vector3f> ring;
  for (int i = 0; i < 10; ++i) ring.emplace_back(2.1f, 0.05f * i, 0.3f);
  PlaneVoxelMap map;
  map.add(map.contributionOf(ring, Eigen::Isometry3d::Identity()));
  const PlaneVoxelMap::Match match = map.match({2.1, 0.2, 0.3}, 0.25);
  EXPECT_TRUE(match.occupied);
  EXPECT_EQ(match.voxel, nullptr);
}

TEST(PlaneVoxelMap, ALookupKeptOverPassesAnswersAsAFreshOne) {
  // A room's corner (two walls and a floor) seen from two poses, one keyframe taken back so that
  // some voxels are emptied; points all around it and beside it, each matched twice (as a
  // registration's passes do), the second time a centimetre off, mostly in the cells the first
  // pass met: the lookup kept over both gives what match() (a lookup used once) gives, exactly.
  PlaneVoxelMap map;
  std::vector<Eigen::Vector3f> corner = voxelWallAt(2.1f);
  for (const auto& p : voxelWallAt(0.3f)) corner.emplace_back(p.y() + 1.3f, p.x() + 0.7f, p.z());
  for (int i = 0; i < 20; ++i) {
    for (int k = 0; k < 20; ++k) corner.emplace_back(1.1f + 0.05f * i, 0.05f * k, 0.02f);
  }
  Eigen::Isometry3d turned = Eigen::Isometry3d::Identity();
  turned.rotate(Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitZ()));
  turned.pretranslate(Eigen::Vector3d(0.04, -0.03, 0.0));
  const auto first = map.contributionOf(corner, Eigen::Isometry3d::Identity());
  const auto second = map.contributionOf(corner, turned);
  const auto third = map.contributionOf(voxelWallAt(3.4f), Eigen::Isometry3d::Identity());
  map.add(first);
  map.add(second);
  map.add(third);
  map.remove(third);
  PlaneVoxelMap::Lookup lookup(map);
  int planes = 0, occupied = 0;
  for (int pass = 0; pass < 2; ++pass) {
    for (int i = 0; i < 40; ++i) {
      for (int j = 0; j < 30; ++j) {
        const Eigen::Vector3d p(0.5 + 0.09 * i + 0.01 * pass, -0.4 + 0.07 * j,
                                0.1 + 0.03 * (i % 9));
        const PlaneVoxelMap::Match expected = map.match(p, 0.25);
        const PlaneVoxelMap::Match got = lookup.match(p, 0.25);
        ASSERT_EQ(got.voxel, expected.voxel) << p.transpose();
        ASSERT_EQ(got.residual, expected.residual) << p.transpose();
        ASSERT_EQ(got.occupied, expected.occupied) << p.transpose();
        planes += expected.voxel != nullptr;
        occupied += expected.occupied;
      }
    }
  }
  // Both kinds of answer were asked for, and points with no plane within reach too.
  EXPECT_GT(planes, 200);
  EXPECT_GT(occupied, 100);
  EXPECT_LT(planes, 2 * 40 * 30);
}

}  // namespace
}  // namespace isg::slam
