#include "slam/sgraph/room_detection.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace isg::slam {
namespace {

// A wall plane facing `normal` through `point`, observed from `from` to `to`.
MapPlane wall(const Eigen::Vector2d& normal, const Eigen::Vector2d& from,
              const Eigen::Vector2d& to) {
  const Eigen::Vector2d mid = 0.5 * (from + to);
  // Seen from 0.4 m below the sensor's base height to 2.5 m above it: a full-height wall.
  return {bim::Plane::throughPoint({normal.x(), normal.y(), 0.0}, {mid.x(), mid.y(), 0.0}),
          from,
          to,
          3,
          -0.4,
          2.5};
}

// The room [0, 4] × [0, 3] with its four walls facing inwards, fully observed.
std::vector<MapPlane> box() {
  return {wall({1, 0}, {0, 0}, {0, 3}), wall({-1, 0}, {4, 0}, {4, 3}), wall({0, 1}, {0, 0}, {4, 0}),
          wall({0, -1}, {0, 3}, {4, 3})};
}

TEST(RoomDetection, FourWallRoomAroundThePoint) {
  const auto room = detectRoom({1.0, 1.0}, box(), 0.0);
  ASSERT_TRUE(room);
  EXPECT_TRUE(room->four_wall);
  EXPECT_NEAR(room->widths[0], 4.0, 1e-9);
  EXPECT_NEAR(room->widths[1], 3.0, 1e-9);
  EXPECT_NEAR((room->centre - Eigen::Vector2d(2.0, 1.5)).norm(), 0.0, 1e-9);
  EXPECT_EQ(room->pairs[0][0], 0);  // the wall behind along +x first
  EXPECT_EQ(room->pairs[0][1], 1);
}

TEST(RoomDetection, WorksWhateverTheBuildingsYaw) {
  const double yaw = 0.7;
  const Eigen::Rotation2Dd R(yaw);
  std::vector<MapPlane> turned;
  for (const auto& w : box()) {
    const Eigen::Vector2d n = R * w.plane.normal.head<2>();
    turned.push_back(wall(n, R * w.start, R * w.end));
  }
  const auto room = detectRoom(R * Eigen::Vector2d(3.0, 2.0), turned, yaw);
  ASSERT_TRUE(room);
  EXPECT_TRUE(room->four_wall);
  EXPECT_NEAR((room->centre - R * Eigen::Vector2d(2.0, 1.5)).norm(), 0.0, 1e-9);
}

TEST(RoomDetection, WallsSeenOnlyInPartAreNotEnoughEvidence) {
  auto walls = box();
  walls[3] = wall({0, -1}, {0, 3}, {1.2, 3});  // the far wall seen over 1.2 of its 4 m
  const auto room = detectRoom({1.0, 1.0}, walls, 0.0);
  // Not a four-wall room; nor a corridor (its walls are not long compared with the gap).
  EXPECT_FALSE(room && room->four_wall);
}

TEST(RoomDetection, CorridorIsATwoWallRoom) {
  // A corridor 1.8 m wide and 12 m long, its ends not seen.
  const std::vector<MapPlane> walls = {wall({0, 1}, {0, 0}, {12, 0}),
                                       wall({0, -1}, {0, 1.8}, {12, 1.8})};
  const auto room = detectRoom({5.0, 0.6}, walls, 0.0);
  ASSERT_TRUE(room);
  EXPECT_FALSE(room->four_wall);
  EXPECT_NEAR(room->widths[0], 1.8, 1e-9);
  // Its centre: on the corridor's mid-line, level with the point.
  EXPECT_NEAR((room->centre - Eigen::Vector2d(5.0, 0.9)).norm(), 0.0, 1e-9);
}

TEST(RoomDetection, LowBoxesOfClutterAreNotWalls) {
  auto walls = box();
  MapPlane clutter = wall({-1, 0}, {2.5, 0.5}, {2.5, 2.0});  // a box's face between the walls
  clutter.z_min = -0.4;
  clutter.z_max = 0.4;
  walls.push_back(clutter);
  const auto room = detectRoom({1.0, 1.0}, walls, 0.0);
  ASSERT_TRUE(room);
  EXPECT_NEAR(room->widths[0], 4.0, 1e-9);
}

TEST(RoomDetection, WallsSeenLowButWhoseTopsWereBeyondViewAreWalls) {
  // A sensor low on the robot sees the walls over 1.0 m only, never their tops.
  auto walls = box();
  for (auto& w : walls) {
    w.z_min = -0.5;
    w.z_max = 0.5;
  }
  EXPECT_FALSE(detectRoom({1.0, 1.0}, walls, 0.0));
  for (auto& w : walls) w.tops_beyond_view = 2;
  auto room = detectRoom({1.0, 1.0}, walls, 0.0);
  ASSERT_TRUE(room);
  EXPECT_TRUE(room->four_wall);
  EXPECT_NEAR(room->widths[0], 4.0, 1e-9);
  // A box seen as low, once also from where the rings above it went over it, is clutter: the
  // room is the walls', not the box's.
  MapPlane clutter = wall({-1, 0}, {2.5, 0.5}, {2.5, 2.0});
  clutter.z_min = -0.5;
  clutter.z_max = 0.5;
  clutter.tops_beyond_view = 1;
  clutter.top_seen_z = 0.5;
  walls.push_back(clutter);
  room = detectRoom({1.0, 1.0}, walls, 0.0);
  ASSERT_TRUE(room);
  EXPECT_NEAR(room->widths[0], 4.0, 1e-9);
  // Before it was overtopped, it was as good as a wall: the room ended at it.
  walls.back().top_seen_z = std::numeric_limits<double>::infinity();
  room = detectRoom({1.0, 1.0}, walls, 0.0);
  ASSERT_TRUE(room);
  EXPECT_NEAR(room->widths[0], 2.5, 1e-9);
}

TEST(RoomDetection, NearestWallsWinAndNarrowGapsAreNoRoom) {
  auto walls = box();
  // A second wall beyond the east one (the next room's far wall, facing the same way).
  walls.push_back(wall({-1, 0}, {8, 0}, {8, 3}));
  const auto room = detectRoom({1.0, 1.0}, walls, 0.0);
  ASSERT_TRUE(room);
  EXPECT_NEAR(room->widths[0], 4.0, 1e-9);
  // Two walls 0.6 m apart are not a room.
  const std::vector<MapPlane> slot = {wall({0, 1}, {0, 0}, {12, 0}),
                                      wall({0, -1}, {0, 0.6}, {12, 0.6})};
  EXPECT_FALSE(detectRoom({5.0, 0.3}, slot, 0.0));
}

}  // namespace
}  // namespace isg::slam
