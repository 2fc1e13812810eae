// A map wall the map could only have seen through another (seenOnlyThroughWalls), by hand: a
// wall along y = 5 (x 0 → 10, seen 50 times, 0.2–2.6 m high) and a keyframe at (5, 0).
#include "slam/deviations/seen_through.hpp"

#include <gtest/gtest.h>

namespace isg::slam {
namespace {

MapWall wallAlongX(int id, double y, double x0, double x1, int observations,
                   std::vector<int> keyframes = {}) {
  MapWall wall;
  wall.id = id;
  wall.normal = -Eigen::Vector3d::UnitY();
  wall.d = y;
  wall.start = {x0, y};
  wall.end = {x1, y};
  wall.z_min = 0.2;
  wall.z_max = 2.6;
  wall.observations = observations;
  wall.keyframes = std::move(keyframes);
  return wall;
}

MapDiagnostics withKeyframeAt(const Eigen::Vector2d& at) {
  MapDiagnostics map;
  MapKeyframe keyframe;
  keyframe.estimate.translation() << at.x(), at.y(), 0.0;
  keyframe.sight.sensor_R << 0.0, 0.0, 0.6;
  map.keyframes.push_back(keyframe);
  return map;
}

TEST(SeenThrough, APlaneBehindAWallSeenManyTimesWasSeenThroughIt) {
  MapDiagnostics map = withKeyframeAt({5.0, 0.0});
  map.walls.push_back(wallAlongX(0, 5.0, 0.0, 10.0, 50));
  const MapWall behind = wallAlongX(1, 5.7, 4.0, 6.0, 1, {0});
  EXPECT_TRUE(seenOnlyThroughWalls(map, behind, 3, 0.2));
  // In front of it, or not known from where it was seen: not.
  EXPECT_FALSE(seenOnlyThroughWalls(map, wallAlongX(1, 4.5, 4.0, 6.0, 1, {0}), 3, 0.2));
  EXPECT_FALSE(seenOnlyThroughWalls(map, wallAlongX(1, 5.7, 4.0, 6.0, 1, {}), 3, 0.2));
  // Within the margin behind it (the same face, fitted a little off): not.
  EXPECT_FALSE(seenOnlyThroughWalls(map, wallAlongX(1, 5.15, 4.0, 6.0, 1, {0}), 3, 0.2));
}

TEST(SeenThrough, ADoorwayAnEndALowWallOrOneSeenTwiceDoNotBlockTheSight) {
  const MapWall behind = wallAlongX(1, 5.7, 4.0, 6.0, 1, {0});
  // A doorway from x = 4.2 to 5.8 in the wall, where the map confirms nothing: the sight line to
  // the middle goes through it.
  MapDiagnostics door = withKeyframeAt({5.0, 0.0});
  door.walls.push_back(wallAlongX(0, 5.0, 0.0, 10.0, 50));
  door.walls[0].confirmed = {{0.0, 4.2}, {5.8, 10.0}};
  EXPECT_FALSE(seenOnlyThroughWalls(door, behind, 3, 0.2));
  // The wall ends at x = 5.5: past its end.
  MapDiagnostics short_wall = withKeyframeAt({5.0, 0.0});
  short_wall.walls.push_back(wallAlongX(0, 5.0, 0.0, 5.5, 50));
  EXPECT_FALSE(seenOnlyThroughWalls(short_wall, behind, 3, 0.2));
  // A parapet 1 m high, under a plane seen up to 2.6 m: seen over it.
  MapDiagnostics low = withKeyframeAt({5.0, 0.0});
  low.walls.push_back(wallAlongX(0, 5.0, 0.0, 10.0, 50));
  low.walls[0].z_max = 1.0;
  EXPECT_FALSE(seenOnlyThroughWalls(low, behind, 3, 0.2));
  // A wall seen twice is no better evidence than the plane behind it.
  MapDiagnostics twice = withKeyframeAt({5.0, 0.0});
  twice.walls.push_back(wallAlongX(0, 5.0, 0.0, 10.0, 2));
  EXPECT_FALSE(seenOnlyThroughWalls(twice, behind, 3, 0.2));
}

}  // namespace
}  // namespace isg::slam
