#include "bim/plan_geometry.hpp"

#include <gtest/gtest.h>

#include "bim/tests/test_plans.hpp"

namespace isg::bim {
namespace {

class TwoRoomGeometry : public ::testing::Test {
 protected:
  Plan plan = testing::parsePlanJson(testing::twoRoomPlanJson());
  const Level& level = plan.levels.front();
  LevelGeometry geometry = computeLevelGeometry(level);

  const WallGeometry& wall(const std::string& id) { return *geometry.findWall(id); }
};

TEST_F(TwoRoomGeometry, AxesAndNormals) {
  const auto& w1 = wall("W1");
  EXPECT_DOUBLE_EQ(w1.length, 6.0);
  EXPECT_EQ(w1.axis, Eigen::Vector2d(1, 0));
  EXPECT_EQ(w1.left_normal, Eigen::Vector2d(0, 1));
  const auto& w3 = wall("W3");  // runs -x: its left is -y, the inside of the building
  EXPECT_EQ(w3.left_normal, Eigen::Vector2d(0, -1));
}

TEST_F(TwoRoomGeometry, EndsExtendToTheFarSideOfTheWallTheyMeet) {
  // Corners: each outer wall continues by half the other's thickness (0.1).
  EXPECT_NEAR(wall("W1").extend_start, 0.1, 1e-12);
  EXPECT_NEAR(wall("W1").extend_end, 0.1, 1e-12);
  // T-junctions: the partition continues through the inner half of the outer wall to its outer
  // face.
  EXPECT_NEAR(wall("W5").extend_start, 0.1, 1e-12);
  EXPECT_NEAR(wall("W5").extend_end, 0.1, 1e-12);
}

TEST_F(TwoRoomGeometry, FacePlanes) {
  // W1's left face is y = 0.1 looking +y: n = (0, 1, 0), d = -0.1.
  const Plane& p = wall("W1").left.plane;
  EXPECT_NEAR((p.normal - Eigen::Vector3d(0, 1, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(p.d, -0.1, 1e-15);
  // W1's right face is y = -0.1 looking -y: n = (0, -1, 0), d = -0.1.
  EXPECT_NEAR((wall("W1").right.plane.normal - Eigen::Vector3d(0, -1, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(wall("W1").right.plane.d, -0.1, 1e-15);
  // W5's left face is x = 2.95 looking -x: n = (-1, 0, 0), d = 2.95.
  EXPECT_NEAR(wall("W5").left.plane.d, 2.95, 1e-12);
  EXPECT_DOUBLE_EQ(wall("W5").left.z_min, 0.0);
  EXPECT_DOUBLE_EQ(wall("W5").left.z_max, 2.8);
}

TEST_F(TwoRoomGeometry, InnerFaceIsInterruptedByTheTJunction) {
  const auto& exposed = wall("W1").left.exposed;
  ASSERT_EQ(exposed.size(), 2u);
  EXPECT_NEAR(exposed[0].lo, 0.1, 1e-9);   // W4's inner face
  EXPECT_NEAR(exposed[0].hi, 2.95, 1e-9);  // W5's west face
  EXPECT_NEAR(exposed[1].lo, 3.05, 1e-9);
  EXPECT_NEAR(exposed[1].hi, 5.9, 1e-9);
}

TEST_F(TwoRoomGeometry, OuterFaceRunsCornerToCorner) {
  const auto& exposed = wall("W1").right.exposed;
  ASSERT_EQ(exposed.size(), 1u);
  EXPECT_NEAR(exposed[0].lo, -0.1, 1e-9);
  EXPECT_NEAR(exposed[0].hi, 6.1, 1e-9);
}

TEST_F(TwoRoomGeometry, OpeningsOnBothFaces) {
  for (const WallFace* face : {&wall("W1").left, &wall("W1").right}) {
    ASSERT_EQ(face->openings.size(), 1u);
    EXPECT_DOUBLE_EQ(face->openings[0].lo, 4.0);
    EXPECT_DOUBLE_EQ(face->openings[0].hi, 5.0);
  }
}

TEST_F(TwoRoomGeometry, FootprintPiecesLeaveTheDoorOpen) {
  // W1 runs from x = -0.1 to 6.1 (its corner extensions), 0.2 thick, with a door at x 4–5.
  const auto pieces = wall("W1").footprintPieces();
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_NEAR((pieces[0][0] - Eigen::Vector2d(-0.1, -0.1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((pieces[0][2] - Eigen::Vector2d(4.0, 0.1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((pieces[1][0] - Eigen::Vector2d(5.0, -0.1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((pieces[1][2] - Eigen::Vector2d(6.1, 0.1)).norm(), 0.0, 1e-12);
  // A wall without a door is one piece: its footprint.
  ASSERT_EQ(wall("W2").footprintPieces().size(), 1u);
  EXPECT_EQ(wall("W2").footprintPieces()[0], wall("W2").footprint());
}

TEST_F(TwoRoomGeometry, RoomsAreBoundedByTheFacesLookingIntoThem) {
  const auto r1 = geometry.boundariesOf("R1");
  ASSERT_EQ(r1.size(), 4u);
  const std::pair<const char*, int> expected[] = {{"W1", +1}, {"W5", +1}, {"W3", +1}, {"W4", +1}};
  for (int e = 0; e < 4; ++e) {
    EXPECT_EQ(r1[e].edge, e);
    EXPECT_EQ(r1[e].wall, expected[e].first);
    EXPECT_EQ(r1[e].side, expected[e].second);
    EXPECT_NEAR(r1[e].distance, 0.0, 1e-12);
  }
  EXPECT_NEAR(r1[0].overlap, 2.85, 1e-9);
  const auto r2 = geometry.boundariesOf("R2");
  ASSERT_EQ(r2.size(), 4u);
  EXPECT_EQ(r2[3].wall, "W5");
  EXPECT_EQ(r2[3].side, -1);  // the partition's right face looks east, into R2
}

TEST_F(TwoRoomGeometry, DoorRoomsAreInferredLeftSideFirst) {
  const Door* d1 = level.findDoor("D1");
  EXPECT_TRUE(d1->rooms_inferred);
  // W5 runs +y, so its left is -x: the west room.
  EXPECT_EQ(d1->rooms[0], "R1");
  EXPECT_EQ(d1->rooms[1], "R2");
  const Door* d2 = level.findDoor("D2");
  EXPECT_FALSE(d2->rooms_inferred);
  EXPECT_EQ(inferDoorRooms(level, *d2), (std::array<std::string, 2>{"R2", "outside"}));
  EXPECT_EQ(doorCentre(level, *d2), Eigen::Vector2d(4.5, 0.0));
}

TEST_F(TwoRoomGeometry, RoomAt) {
  EXPECT_EQ(roomAt(level, {1, 1}), "R1");
  EXPECT_EQ(roomAt(level, {5, 3}), "R2");
  EXPECT_FALSE(roomAt(level, {3.0, 1}));  // inside the partition
  EXPECT_FALSE(roomAt(level, {-1, 1}));
}

TEST(PlanGeometry, CollinearWallsInARowDoNotCutEachOther) {
  auto doc = testing::twoRoomPlanJson();
  auto& walls = doc["levels"][0]["walls"];
  // Split W1 into two collinear halves meeting at x = 3.
  walls[0]["end"] = {3, 0};
  walls.push_back({{"id", "W1b"}, {"start", {3, 0}}, {"end", {6, 0}}, {"thickness", 0.2}});
  doc["levels"][0]["doors"][1]["wall"] = "W1b";
  doc["levels"][0]["doors"][1]["offset"] = 1.5;
  const Plan plan = testing::parsePlanJson(doc);
  const LevelGeometry g = computeLevelGeometry(plan.levels.front());
  // W1 ends where the partition W5 meets it, so its solid reaches W5's far face at x = 3.05 and
  // W1b's starts at W5's near face, x = 2.95; neither cuts the other's outer face (y = -0.1).
  const auto& outer = g.findWall("W1")->right.exposed;
  ASSERT_EQ(outer.size(), 1u);
  EXPECT_NEAR(outer[0].lo, -0.1, 1e-9);
  EXPECT_NEAR(outer[0].hi, 3.05, 1e-9);
  const auto& outer_b = g.findWall("W1b")->right.exposed;
  ASSERT_EQ(outer_b.size(), 1u);
  EXPECT_NEAR(outer_b[0].lo, -0.05, 1e-9);
  EXPECT_NEAR(outer_b[0].hi, 3.1, 1e-9);
}

TEST(PlanGeometry, EllShapedRoomIsBoundedOnAllSixSides) {
  const nlohmann::json doc = nlohmann::json::parse(R"({
    "format": "isg.plan", "version": 1,
    "levels": [{"id": "L0", "height": 3,
      "walls": [
        {"id": "A", "start": [0, 0], "end": [4, 0], "thickness": 0.2},
        {"id": "B", "start": [4, 0], "end": [4, 2], "thickness": 0.2},
        {"id": "C", "start": [4, 2], "end": [2, 2], "thickness": 0.2},
        {"id": "D", "start": [2, 2], "end": [2, 4], "thickness": 0.2},
        {"id": "E", "start": [2, 4], "end": [0, 4], "thickness": 0.2},
        {"id": "F", "start": [0, 4], "end": [0, 0], "thickness": 0.2}
      ],
      "rooms": [{"id": "L", "outline": [[0.1, 0.1], [3.9, 0.1], [3.9, 1.9], [1.9, 1.9], [1.9, 3.9], [0.1, 3.9]]}]
    }]})");
  const Plan plan = testing::parsePlanJson(doc);
  const LevelGeometry g = computeLevelGeometry(plan.levels.front());
  const auto bounds = g.boundariesOf("L");
  ASSERT_EQ(bounds.size(), 6u);
  const char* walls = "ABCDEF";
  for (int e = 0; e < 6; ++e) {
    EXPECT_EQ(bounds[e].wall, std::string(1, walls[e]));
    EXPECT_EQ(bounds[e].side, +1);
  }
  // The re-entrant corner: C and D meet at (2, 2); C's inner face (y = 1.9) runs from x = 3.9
  // back to x = 1.9, i.e. axis coordinates [0.1, 2.1].
  const auto& c_inner = g.findWall("C")->left.exposed;
  ASSERT_EQ(c_inner.size(), 1u);
  EXPECT_NEAR(c_inner[0].lo, 0.1, 1e-9);
  EXPECT_NEAR(c_inner[0].hi, 2.1, 1e-9);
}

}  // namespace
}  // namespace isg::bim
