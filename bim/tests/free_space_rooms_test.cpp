// Rooms from the free space walls enclose (bim/free_space_rooms), against rooms known by hand.
#include "bim/free_space_rooms.hpp"

#include <gtest/gtest.h>

#include <string>

#include "bim/plan_parser.hpp"
#include "bim/tests/test_plans.hpp"

namespace isg::bim {
namespace {

// The outline's bounding box.
std::pair<Eigen::Vector2d, Eigen::Vector2d> boxOf(const Polygon2& outline) {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300), hi = -lo;
  for (const auto& p : outline) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  return {lo, hi};
}

TEST(FreeSpaceRooms, TheTwoRoomBoxGivesItsTwoRoomsAtTheWallFaces) {
  const Plan plan = testing::parsePlanJson(testing::twoRoomPlanJson());
  const FreeSpaceRooms rooms = enclosedFreeSpaces(plan.levels[0]);
  ASSERT_EQ(rooms.outlines.size(), 2u);
  EXPECT_EQ(rooms.pockets, 0);
  EXPECT_DOUBLE_EQ(rooms.cell, 0.05);
  // West: inside faces x 0.1 … 2.95, y 0.1 … 3.9 (the partition is 0.1 thick at x = 3); East:
  // 3.05 … 5.9. The door in the partition does not join them. Traced along cell edges: within
  // one cell of the faces.
  const auto [west_lo, west_hi] = boxOf(rooms.outlines[0]);
  const auto [east_lo, east_hi] = boxOf(rooms.outlines[1]);
  EXPECT_NEAR(west_lo.x(), 0.1, 0.05);
  EXPECT_NEAR(west_hi.x(), 2.95, 0.05);
  EXPECT_NEAR(west_lo.y(), 0.1, 0.05);
  EXPECT_NEAR(west_hi.y(), 3.9, 0.05);
  EXPECT_NEAR(east_lo.x(), 3.05, 0.05);
  EXPECT_NEAR(east_hi.x(), 5.9, 0.05);
  for (const auto& outline : rooms.outlines) {
    EXPECT_EQ(outline.size(), 4u);  // a rectangle's four corners
    EXPECT_GT(signedArea(outline), 0.0);
    EXPECT_FALSE(findSelfIntersection(outline));
  }
  EXPECT_NEAR(signedArea(rooms.outlines[0]), 2.85 * 3.8, 0.05 * (2.85 + 3.8) * 2);
}

TEST(FreeSpaceRooms, ADiagonalWallIsStraightenedAndSmallPocketsAreNoRooms) {
  // A triangle of walls (one at 45°) and a 0.5 m × 0.5 m closet in its corner.
  auto document = nlohmann::json::parse(R"({
    "format": "isg.plan", "version": 1,
    "levels": [{"id": "L0", "elevation": 0, "height": 3, "walls": [
      {"id": "A", "start": [0, 0], "end": [8, 0], "thickness": 0.2},
      {"id": "B", "start": [8, 0], "end": [0, 8], "thickness": 0.2},
      {"id": "C", "start": [0, 8], "end": [0, 0], "thickness": 0.2},
      {"id": "D", "start": [0.6, 0], "end": [0.6, 0.6], "thickness": 0.1},
      {"id": "E", "start": [0.6, 0.6], "end": [0, 0.6], "thickness": 0.1}
    ]}]})");
  const Plan plan = testing::parsePlanJson(document);
  const FreeSpaceRooms rooms = enclosedFreeSpaces(plan.levels[0]);
  ASSERT_EQ(rooms.outlines.size(), 1u);
  EXPECT_EQ(rooms.pockets, 1);  // the closet: 0.45 × 0.45 m inside
  const Polygon2& room = rooms.outlines[0];
  EXPECT_LE(room.size(), 8u) << "the 45° face traced as a staircase, then straightened";
  // The inside of the triangle: x ≥ 0.1, y ≥ 0.1, x + y ≤ 8 − 0.1·√2 (legs 7.66 m), less the
  // corner the closet's walls take (x, y < 0.65: 0.55 m square).
  const double leg = 8.0 - 0.2 - 0.1 * std::sqrt(2.0);
  EXPECT_NEAR(signedArea(room), 0.5 * leg * leg - 0.55 * 0.55, 0.3);
}

}  // namespace
}  // namespace isg::bim
