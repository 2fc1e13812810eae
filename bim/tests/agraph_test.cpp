#include "bim/agraph.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bim/plan_parser.hpp"
#include "bim/plan_transform.hpp"
#include "bim/polygon.hpp"
#include "bim/synthetic_plan.hpp"
#include "bim/tests/test_plans.hpp"

namespace isg::bim {
namespace {

const std::string kAGraphPlans = std::string(ISG_SOURCE_DIR) + "/worlds/plans/";

class TwoRoomAGraph : public ::testing::Test {
 protected:
  Plan plan = testing::parsePlanJson(testing::twoRoomPlanJson());
  AGraph graph = buildAGraph(plan);
  const WallSurfaceNode& surface(const std::string& id) {
    return graph.surfaces[graph.findSurface(id)];
  }
  const RoomNode& room(const std::string& id) { return graph.rooms[graph.findRoom(id)]; }
};

TEST_F(TwoRoomAGraph, NodeCounts) {
  EXPECT_EQ(graph.surfaces.size(), 10u);  // five walls, two faces each
  EXPECT_EQ(graph.walls.size(), 5u);
  EXPECT_EQ(graph.rooms.size(), 2u);
  EXPECT_EQ(graph.doorways.size(), 2u);
  ASSERT_EQ(graph.floors.size(), 1u);
}

TEST_F(TwoRoomAGraph, SurfaceBoundsAreTheOuterFacesOfTheOuterWalls) {
  // The outer walls are 0.2 m thick about lines x ∈ {0, 6}, y ∈ {0, 4}: their outer faces.
  const Eigen::AlignedBox2d bounds = graph.surfaceBounds();
  EXPECT_NEAR((bounds.min() - Eigen::Vector2d(-0.1, -0.1)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((bounds.max() - Eigen::Vector2d(6.1, 4.1)).norm(), 0.0, 1e-9);
  EXPECT_TRUE(AGraph{}.surfaceBounds().isEmpty());
}

TEST_F(TwoRoomAGraph, TheLocalOriginIsTheMiddleOfTheWallsToTheMetre) {
  // Bounds (−0.1, −0.1) … (6.1, 4.1): the middle (3, 2).
  EXPECT_NEAR((graph.localOrigin() - Eigen::Vector2d(3.0, 2.0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(AGraph{}.localOrigin().norm(), 0.0, 0.0);
  // Moved by (7999.6, −8000.2), the middle (8002.6, −7998.2) rounds to (8003, −7998).
  const Eigen::Vector2d shift(7999.6, -8000.2);
  EXPECT_NEAR((graph.translated(shift).localOrigin() - Eigen::Vector2d(8003.0, -7998.0)).norm(),
              0.0, 1e-12);
}

TEST_F(TwoRoomAGraph, TranslatedIsTheGraphOfTheMovedPlan) {
  // Moving the graph is building the graph of the moved plan, node for node.
  const Eigen::Vector2d shift(-8000.0, 7999.5);
  const AGraph moved = graph.translated(shift);
  const AGraph rebuilt = buildAGraph(transformedPlan(plan, planarMotion(shift, 0.0)));
  ASSERT_EQ(moved.surfaces.size(), rebuilt.surfaces.size());
  for (std::size_t i = 0; i < moved.surfaces.size(); ++i) {
    EXPECT_EQ(moved.surfaces[i].id, rebuilt.surfaces[i].id);
    EXPECT_NEAR((moved.surfaces[i].plane.normal - rebuilt.surfaces[i].plane.normal).norm(), 0,
                1e-12);
    EXPECT_NEAR(moved.surfaces[i].plane.d, rebuilt.surfaces[i].plane.d, 1e-9);
    ASSERT_EQ(moved.surfaces[i].segments.size(), rebuilt.surfaces[i].segments.size());
    for (std::size_t k = 0; k < moved.surfaces[i].segments.size(); ++k) {
      EXPECT_NEAR(
          (moved.surfaces[i].segments[k].first - rebuilt.surfaces[i].segments[k].first).norm(), 0,
          1e-9);
    }
  }
  ASSERT_EQ(moved.walls.size(), rebuilt.walls.size());
  for (std::size_t i = 0; i < moved.walls.size(); ++i) {
    EXPECT_NEAR((moved.walls[i].centre - rebuilt.walls[i].centre).norm(), 0, 1e-9);
    EXPECT_NEAR((moved.walls[i].anchor - rebuilt.walls[i].anchor).norm(), 0, 1e-9);
  }
  ASSERT_EQ(moved.rooms.size(), rebuilt.rooms.size());
  for (std::size_t i = 0; i < moved.rooms.size(); ++i) {
    EXPECT_NEAR((moved.rooms[i].centre - rebuilt.rooms[i].centre).norm(), 0, 1e-9);
    EXPECT_NEAR((moved.rooms[i].axis_point - rebuilt.rooms[i].axis_point).norm(), 0, 1e-9);
  }
  ASSERT_EQ(moved.doorways.size(), rebuilt.doorways.size());
  for (std::size_t i = 0; i < moved.doorways.size(); ++i) {
    EXPECT_NEAR((moved.doorways[i].position - rebuilt.doorways[i].position).norm(), 0, 1e-9);
  }
  EXPECT_NEAR((moved.floors[0].centre - rebuilt.floors[0].centre).norm(), 0, 1e-9);
  // And the wall centres still satisfy Eq. (1) on the moved planes.
  for (const auto& wall : moved.walls) {
    const Eigen::Vector3d f = wallCentre(moved.surfaces[wall.left_surface].plane,
                                         moved.surfaces[wall.right_surface].plane, wall.anchor);
    EXPECT_NEAR((f - wall.centre).norm(), 0.0, 1e-9) << wall.id;
  }
}

TEST_F(TwoRoomAGraph, SurfacesArePlanesOfTheFacesWithTheirExposedParts) {
  const auto& s =
      surface("W1:left");  // y = 0.1, looking +y, between W4 and the partition and beyond
  EXPECT_EQ(s.axis, SurfaceAxis::kY);
  EXPECT_NEAR((s.plane.normal - Eigen::Vector3d(0, 1, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(s.plane.d, -0.1, 1e-12);
  ASSERT_EQ(s.segments.size(), 2u);
  EXPECT_NEAR((s.segments[0].first - Eigen::Vector2d(0.1, 0.1)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((s.segments[0].second - Eigen::Vector2d(2.95, 0.1)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(s.exposedLength(), 2.85 + 2.85, 1e-9);
  EXPECT_DOUBLE_EQ(s.z_max, 3.0);
  EXPECT_EQ(surface("W5:left").axis, SurfaceAxis::kX);
  EXPECT_NEAR(surface("W5:left").plane.d, 2.95, 1e-12);  // x = 2.95 looking -x
}

TEST_F(TwoRoomAGraph, WallCentreFollowsEquationOne) {
  // W1: faces y = ±0.1, so ½(cp₁ + cp₂) = (0, 0, 0); the anchor is the axis midpoint (3, 0) at
  // half the wall's height, whose in-plane part is (3, 0, 1.5): ω = (3, 0, 1.5).
  const WallNode& w1 = graph.walls[0];
  EXPECT_NEAR((w1.centre - Eigen::Vector3d(3, 0, 1.5)).norm(), 0.0, 1e-12);
  // W5 (x = 3, 2.8 m high): faces x = 2.95 and 3.05 → mid (3, 0, 0); anchor (3, 2, 1.4).
  const WallNode& w5 = graph.walls[4];
  EXPECT_NEAR((w5.centre - Eigen::Vector3d(3, 2, 1.4)).norm(), 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(w5.thickness, 0.1);
  EXPECT_DOUBLE_EQ(w5.length, 4.0);
}

TEST_F(TwoRoomAGraph, FourWallRoomsWithCentresAndWidths) {
  const RoomNode& west = room("R1");
  EXPECT_EQ(west.kind, RoomKind::kFourWall);
  // x pair (outline edges 1 and 3): W5's face x = 2.95 and W4's x = 0.1; y pair (edges 0 and 2):
  // W1's y = 0.1 and W3's y = 3.9.
  ASSERT_EQ(west.pairs.size(), 2u);
  EXPECT_EQ(graph.surfaces[west.pairs[0][0]].id, "W5:left");
  EXPECT_EQ(graph.surfaces[west.pairs[0][1]].id, "W4:left");
  EXPECT_EQ(graph.surfaces[west.pairs[1][0]].id, "W1:left");
  EXPECT_EQ(graph.surfaces[west.pairs[1][1]].id, "W3:left");
  EXPECT_NEAR(west.widths[0], 2.85, 1e-12);
  EXPECT_NEAR(west.widths[1], 3.8, 1e-12);
  EXPECT_NEAR((west.centre - Eigen::Vector2d(1.525, 2.0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((room("R2").centre - Eigen::Vector2d(4.475, 2.0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(graph.surfaces[room("R2").surfaces[3]].id, "W5:right");
}

TEST_F(TwoRoomAGraph, DoorwaysAndFloor) {
  const DoorwayNode& d1 = graph.doorways[0];
  EXPECT_EQ(d1.id, "D1");
  EXPECT_NEAR((d1.position - Eigen::Vector3d(3, 2, 0)).norm(), 0.0, 1e-12);
  ASSERT_EQ(d1.rooms.size(), 2u);
  EXPECT_EQ(graph.rooms[d1.rooms[0]].id, "R1");
  EXPECT_EQ(graph.rooms[d1.rooms[1]].id, "R2");
  const DoorwayNode& d2 = graph.doorways[1];
  ASSERT_EQ(d2.rooms.size(), 1u);  // R2 and the outside
  EXPECT_NEAR((d2.position - Eigen::Vector3d(4.5, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((graph.floors[0].centre - Eigen::Vector2d(3.0, 2.0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(graph.floors[0].rooms.size(), 2u);
}

TEST(AGraph, CorridorIsATwoWallRoom) {
  const AGraph graph = buildAGraph(loadPlan(kAGraphPlans + "d1.json"));
  const RoomNode& corridor = graph.rooms[graph.findRoom("R4")];
  EXPECT_EQ(corridor.kind, RoomKind::kTwoWall);
  ASSERT_EQ(corridor.pairs.size(), 1u);
  EXPECT_EQ(graph.surfaces[corridor.pairs[0][0]].id, "W1:left");   // y = 0.15
  EXPECT_EQ(graph.surfaces[corridor.pairs[0][1]].id, "W5:right");  // y = 2.125
  EXPECT_NEAR(corridor.widths[0], 1.975, 1e-12);
  // The centre: the corridor's mid-plane y = 1.1375 at the outline's centroid x = 6.
  EXPECT_NEAR((corridor.centre - Eigen::Vector2d(6.0, 1.1375)).norm(), 0.0, 1e-9);
  for (const char* office : {"R1", "R2", "R3"}) {
    EXPECT_EQ(graph.rooms[graph.findRoom(office)].kind, RoomKind::kFourWall) << office;
  }
}

// D1 sheared along x by 30° (x += y·tan 30°): its corridor along x becomes a parallelogram with
// leaning ends, still a corridor between the same two faces 1.975 m apart; its offices become
// parallelograms, polygons (no four-wall room factor holds for them).
TEST(AGraph, AShearedCorridorIsStillATwoWallRoom) {
  Plan plan = loadPlan(kAGraphPlans + "d1.json");
  const double lean = std::tan(30.0 * std::numbers::pi / 180.0);
  const auto shear = [&](const Eigen::Vector2d& p) {
    return Eigen::Vector2d(p.x() + lean * p.y(), p.y());
  };
  for (Wall& wall : plan.levels[0].walls) {
    const double before = (wall.end - wall.start).norm();
    wall.start = shear(wall.start);
    wall.end = shear(wall.end);
    const double stretch = (wall.end - wall.start).norm() / before;
    wall.thickness /= stretch;  // the shear keeps areas: the faces stay on the outlines
    for (Door& door : plan.levels[0].doors) {
      if (door.wall == wall.id) door.offset *= stretch, door.width *= stretch;
    }
  }
  for (Room& room : plan.levels[0].rooms) {
    for (Eigen::Vector2d& vertex : room.outline) vertex = shear(vertex);
  }
  const AGraph graph = buildAGraph(plan);
  const RoomNode& corridor = graph.rooms[graph.findRoom("R4")];
  EXPECT_EQ(corridor.kind, RoomKind::kTwoWall);
  ASSERT_EQ(corridor.pairs.size(), 1u);
  EXPECT_EQ(graph.surfaces[corridor.pairs[0][0]].id, "W1:left");
  EXPECT_EQ(graph.surfaces[corridor.pairs[0][1]].id, "W5:right");
  EXPECT_NEAR(corridor.widths[0], 1.975, 1e-9);
  // On the corridor's mid-plane y = 1.1375, at the sheared outline's centroid.
  EXPECT_NEAR(corridor.centre.y(), 1.1375, 1e-9);
  EXPECT_NEAR(corridor.centre.x(), centroid(corridor.outline).x(), 1e-9);
  for (const char* office : {"R1", "R2", "R3"}) {
    EXPECT_EQ(graph.rooms[graph.findRoom(office)].kind, RoomKind::kPolygon) << office;
  }
}

TEST(AGraph, EllShapedHallKeepsItsSixSurfaces) {
  const AGraph graph = buildAGraph(loadPlan(kAGraphPlans + "d5.json"));
  const RoomNode& hall = graph.rooms[graph.findRoom("R1")];
  EXPECT_EQ(hall.kind, RoomKind::kPolygon);
  ASSERT_EQ(hall.surfaces.size(), 6u);
  for (int s : hall.surfaces) EXPECT_GE(s, 0);
  EXPECT_TRUE(hall.pairs.empty());
  EXPECT_EQ(graph.rooms[graph.findRoom("R3")].kind, RoomKind::kTwoWall);  // the 8 × 2.5 passage
}

TEST(AGraph, EveryReferencePlanHasItsRoomsAndDoorways) {
  struct Expected {
    const char* plan;
    int rooms, four_wall, two_wall, polygon, doorways;
  };
  for (const auto& e : {Expected{"d1", 4, 3, 1, 0, 5}, Expected{"d2", 3, 3, 0, 0, 3},
                        Expected{"d3", 8, 7, 1, 0, 8}, Expected{"d4", 8, 7, 1, 0, 9},
                        Expected{"d5", 6, 4, 1, 1, 7}, Expected{"d6", 17, 15, 2, 0, 20}}) {
    const Plan plan = loadPlan(kAGraphPlans + e.plan + ".json");
    const AGraph graph = buildAGraph(plan);
    int counts[3] = {0, 0, 0};
    for (const auto& r : graph.rooms) ++counts[int(r.kind)];
    EXPECT_EQ(int(graph.rooms.size()), e.rooms) << e.plan;
    EXPECT_EQ(counts[0], e.four_wall) << e.plan;
    EXPECT_EQ(counts[1], e.two_wall) << e.plan;
    EXPECT_EQ(counts[2], e.polygon) << e.plan;
    EXPECT_EQ(int(graph.doorways.size()), e.doorways) << e.plan;
    EXPECT_EQ(graph.surfaces.size(), 2 * plan.levels[0].walls.size()) << e.plan;
    for (const auto& d : graph.doorways) EXPECT_FALSE(d.rooms.empty()) << e.plan << " " << d.id;
  }
}

TEST(AGraph, TwoHundredRoomGrid) {
  const Plan plan = testing::parsePlanJson(makeGridPlan({}));
  const AGraph graph = buildAGraph(plan);
  EXPECT_EQ(graph.rooms.size(), 200u);
  for (const auto& r : graph.rooms) {
    EXPECT_EQ(r.kind, RoomKind::kFourWall) << r.id;
    // Room centres from the factor's function equal the outline centroids (outlines on faces).
    const Eigen::Vector2d c = (r.outline[0] + r.outline[2]) / 2;
    EXPECT_NEAR((r.centre - c).norm(), 0.0, 1e-9) << r.id;
  }
  // Long walls bound many rooms: H1 runs the whole width, split into 20 pieces per face.
  const auto& h1 = graph.surfaces[graph.findSurface("H1:left")];
  EXPECT_EQ(h1.segments.size(), 20u);
}

}  // namespace
}  // namespace isg::bim

namespace isg::bim {
namespace {

// A flight rising from L0 (storeys: S1 from (9, 0.85) to (13.5, 0.85), 1 m wide, to L1 at
// 3.2 m) stands on L0 like a wall: its two sides and its high end are L0 surfaces, facing away
// from it, as high as it rises; L1, which it opens into, has none.
TEST(FlightFaces, AFlightIsSeenOnTheLevelItRisesFrom) {
  const AGraph graph = buildAGraph(loadPlan(kAGraphPlans + "storeys.json"));
  const int left = graph.findSurface("S1:stair-left");
  const int right = graph.findSurface("S1:stair-right");
  const int end = graph.findSurface("S1:stair-end");
  ASSERT_GE(left, 0);
  ASSERT_GE(right, 0);
  ASSERT_GE(end, 0);
  const Eigen::Vector3d on_left(11.0, 1.35, 1.0), on_right(11.0, 0.35, 1.0),
      on_end(13.5, 0.85, 1.0);
  EXPECT_NEAR(graph.surfaces[left].plane.signedDistance(on_left), 0.0, 1e-12);
  EXPECT_NEAR(graph.surfaces[left].plane.signedDistance({11.0, 2.0, 1.0}), 0.65, 1e-12);
  EXPECT_NEAR(graph.surfaces[right].plane.signedDistance(on_right), 0.0, 1e-12);
  EXPECT_NEAR(graph.surfaces[right].plane.signedDistance({11.0, 0.0, 1.0}), 0.35, 1e-12);
  EXPECT_NEAR(graph.surfaces[end].plane.signedDistance(on_end), 0.0, 1e-12);
  EXPECT_NEAR(graph.surfaces[end].plane.signedDistance({14.0, 0.85, 1.0}), 0.5, 1e-12);
  for (int s : {left, right, end}) {
    const WallSurfaceNode& face = graph.surfaces[s];
    EXPECT_EQ(face.level, "L0");
    EXPECT_EQ(face.stair, "S1");
    EXPECT_TRUE(face.wall.empty());
    EXPECT_DOUBLE_EQ(face.z_min, 0.0);
    EXPECT_DOUBLE_EQ(face.z_max, 3.2);
    ASSERT_EQ(face.segments.size(), 1u);
  }
  EXPECT_NEAR(
      (graph.surfaces[left].segments[0].second - graph.surfaces[left].segments[0].first).norm(),
      4.5, 1e-12);
  EXPECT_NEAR(
      (graph.surfaces[end].segments[0].second - graph.surfaces[end].segments[0].first).norm(), 1.0,
      1e-12);
  EXPECT_EQ(graph.surfaces[end].axis, SurfaceAxis::kX);
  for (const auto& surface : graph.surfaces) {
    if (surface.level == "L1") {
      EXPECT_TRUE(surface.stair.empty()) << surface.id;
    }
  }
  // No room or wall refers to them.
  for (const auto& wall : graph.walls) {
    EXPECT_NE(wall.left_surface, left);
    EXPECT_NE(wall.right_surface, end);
  }
}

}  // namespace
}  // namespace isg::bim
