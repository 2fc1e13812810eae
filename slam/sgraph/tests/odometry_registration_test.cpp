// The odometry's registration against its voxel map of planes: the scan's height against the
// map's floors and ceilings (levelOffset).

#include "slam/sgraph/odometry_registration.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "slam/sgraph/plane_voxel_map.hpp"
#include "slam/sgraph/tests/box_world.hpp"

namespace isg::slam {
namespace {

TEST(LevelOffset, AScanPlacedTooLowIsThatMuchBelowTheFloorAndCeiling) {
  // The box room's map seen from 1 m above its floor (z = 0 in M) at eight places 0.3 m apart
  // along x (one scan's rings are lines on the floor, not planes: it takes several); a scan taken
  // 0.12 m higher but placed at z = 0 lies 0.12 m below the floor and the ceiling; placed where it
  // was taken, on them. The walls give no height.
  PlaneVoxelMap map, walls;
  for (int k = 0; k < 8; ++k) {
    Eigen::Isometry3d M_T_L = Eigen::Isometry3d::Identity();
    M_T_L.translation().x() = 0.3 * k;
    std::vector<Eigen::Vector3f> cloud;
    for (const auto& p : testing::boxScan(M_T_L, 0.0).points) cloud.emplace_back(p.x, p.y, p.z);
    map.add(map.contributionOf(cloud, M_T_L));
    // The walls' map: the floor's and the ceiling's points left out.
    std::erase_if(cloud, [](const Eigen::Vector3f& p) { return p.z() < -0.99f || p.z() > 1.99f; });
    walls.add(walls.contributionOf(cloud, M_T_L));
  }
  Eigen::Isometry3d higher = Eigen::Isometry3d::Identity();
  higher.translation() = Eigen::Vector3d(1.0, 0.0, 0.12);
  Eigen::Isometry3d placed_low = higher;
  placed_low.translation().z() = 0.0;
  std::vector<Eigen::Vector3f> scan;
  for (const auto& p : testing::boxScan(higher, 0.1).points) scan.emplace_back(p.x, p.y, p.z);

  const LevelOffset low = levelOffset(scan, placed_low, map, 0.25, 0.1, 0.9);
  EXPECT_NEAR(low.offset, -0.12, 0.005);
  EXPECT_GT(low.points, 1000);
  EXPECT_LT(low.spread, 0.01);
  const LevelOffset placed = levelOffset(scan, higher, map, 0.25, 0.1, 0.9);
  EXPECT_NEAR(placed.offset, 0.0, 0.005);
  // A map of walls alone says nothing of the height.
  EXPECT_EQ(levelOffset(scan, placed_low, walls, 0.25, 0.1, 0.9).points, 0);
}

}  // namespace
}  // namespace isg::slam
