#include "run/foxglove/run_scene.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

namespace isg::run {
namespace {

using Json = nlohmann::json;

// One wall W1 along x on a storey at 3 m, a doorway in it, a room beside it.
Json handAGraph() {
  return Json::parse(R"({
    "nodes": {
      "wall_surfaces": [{"id": "W1:left", "wall": "W1", "level": "L1",
                         "plane": {"n": [0.0, 1.0, 0.0], "d": -0.1},
                         "segments": [[[0.0, 0.1], [4.0, 0.1]]], "z": [3.0, 6.0]}],
      "walls": [{"id": "W1", "level": "L1", "centre": [2.0, 0.0, 4.5], "thickness": 0.2}],
      "rooms": [{"id": "R1", "name": "Office", "level": "L1", "centre": [2.0, 2.0],
                 "outline": [[0, 0.1], [4, 0.1], [4, 4], [0, 4]]}],
      "doorways": [{"id": "D1", "wall": "W1", "level": "L1", "position": [2.0, 0.0, 3.0],
                    "width": 0.9}],
      "floors": [{"id": "L1", "elevation": 3.0, "centre": [2.0, 2.0]}]
    },
    "edges": [{"type": "wall_surface", "from": "W1", "to": "W1:left"},
              {"type": "floor_room", "from": "L1", "to": "R1"},
              {"type": "doorway_room", "from": "D1", "to": "R9"}]
  })");
}

const Json* entity(const std::vector<Json>& entities, const std::string& id) {
  for (const Json& e : entities) {
    if (e["id"] == id) return &e;
  }
  return nullptr;
}

Eigen::Vector3d point(const Json& p) {
  return {p["x"].get<double>(), p["y"].get<double>(), p["z"].get<double>()};
}

TEST(RunScene, ThePlanDrawsWallFacesDoorwaysAndRoomsOnTheirStorey) {
  const auto plan = planEntities(handAGraph(), formats::RosTime{5, 0});
  ASSERT_EQ(plan.size(), 3u);
  const Json& faces = (*entity(plan, "plan/walls"))["triangles"][0]["points"];
  ASSERT_EQ(faces.size(), 6u);  // one segment: two triangles
  EXPECT_EQ(point(faces[0]), Eigen::Vector3d(0, 0.1, 3));
  EXPECT_EQ(point(faces[1]), Eigen::Vector3d(4, 0.1, 3));
  EXPECT_EQ(point(faces[2]), Eigen::Vector3d(4, 0.1, 6));
  EXPECT_EQ(point(faces[5]), Eigen::Vector3d(0, 0.1, 6));

  const Json& door = (*entity(plan, "plan/doorways"))["cubes"][0];
  EXPECT_NEAR(door["pose"]["position"]["z"].get<double>(), 3.01, 1e-12);
  // Turned to the wall's normal (+y): 90° about z; across the wall 0.2 + 0.2 m, along it 0.9 m.
  EXPECT_NEAR(door["pose"]["orientation"]["z"].get<double>(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(door["size"]["x"].get<double>(), 0.4, 1e-12);
  EXPECT_NEAR(door["size"]["y"].get<double>(), 0.9, 1e-12);

  const Json& rooms = *entity(plan, "plan/rooms");
  EXPECT_EQ(rooms["lines"][0]["points"].size(), 4u);
  EXPECT_EQ(rooms["texts"][0]["text"], "R1 Office");
  EXPECT_NEAR(rooms["texts"][0]["pose"]["position"]["z"].get<double>(), 3.32, 1e-12);
  EXPECT_EQ(rooms["timestamp"]["sec"], 5u);
}

TEST(RunScene, TheAGraphStandsInLayersAboveItsStorey) {
  const auto agraph = agraphEntities(handAGraph(), formats::RosTime{});
  const Json& spheres = (*entity(agraph, "agraph/nodes"))["spheres"];
  ASSERT_EQ(spheres.size(), 5u);  // surface, wall, room, doorway, floor
  // The surface at the middle of its segment, at its top; the wall at 3 + kWallLayerHeight.
  EXPECT_EQ(point(spheres[0]["pose"]["position"]), Eigen::Vector3d(2, 0.1, 6));
  EXPECT_EQ(point(spheres[1]["pose"]["position"]), Eigen::Vector3d(2, 0, 3 + kWallLayerHeight));
  EXPECT_EQ(point(spheres[2]["pose"]["position"]), Eigen::Vector3d(2, 2, 3 + kRoomLayerHeight));
  EXPECT_EQ(point(spheres[4]["pose"]["position"]), Eigen::Vector3d(2, 2, 3 + kFloorLayerHeight));
  // Two edges drawn; the one to a room that is not there is left out.
  EXPECT_EQ((*entity(agraph, "agraph/edges"))["lines"][0]["points"].size(), 4u);
}

TEST(RunScene, TheSGraphDrawsPlanesRoomsAndTheirEdgesInTheMap) {
  const Json sgraph = Json::parse(R"({
    "keyframes": [{"position": [0.5, 0.5, 0.0], "plane_ids": [0, 7]},
                  {"position": [1.5, 0.5, 0.0]}],
    "planes": [{"id": 0, "floor": 0, "start": [0.0, 0.0], "end": [2.0, 0.0]}],
    "rooms": [{"id": 0, "floor": 0, "centre": [1.0, 1.0], "plane_pairs": [[0, 1]]}],
    "floors": [{"id": 0, "height": -0.5, "centre": [1.0, 1.0]}]
  })");
  const auto drawn = sgraphEntities(sgraph, formats::RosTime{});
  ASSERT_EQ(drawn.size(), 5u);
  for (const Json& e : drawn) EXPECT_EQ(e["frame_id"], "map");
  EXPECT_EQ((*entity(drawn, "sgraph/keyframes"))["spheres"].size(), 2u);
  const Json& quad = (*entity(drawn, "sgraph/planes"))["triangles"][0]["points"];
  EXPECT_EQ(point(quad[0]), Eigen::Vector3d(0, 0, -0.5));
  EXPECT_EQ(point(quad[2]), Eigen::Vector3d(2, 0, -0.5 + kPlaneDrawHeight));
  // The first keyframe to plane 0's middle (plane 7 is not in the graph); plane 0's top middle
  // to the room, the room to the floor (plane 1 is not in the graph either).
  const Json& edges = (*entity(drawn, "sgraph/edges"))["lines"][0]["points"];
  ASSERT_EQ(edges.size(), 6u);
  EXPECT_EQ(point(edges[0]), Eigen::Vector3d(0.5, 0.5, 0));
  EXPECT_EQ(point(edges[1]), Eigen::Vector3d(1, 0, -0.5 + kPlaneDrawHeight / 2));
  EXPECT_EQ(point(edges[2]), Eigen::Vector3d(1, 0, -0.5 + kPlaneDrawHeight));
  EXPECT_EQ(point(edges[3]), Eigen::Vector3d(1, 1, -0.5 + kRoomLayerHeight));
  EXPECT_EQ(point(edges[5]), Eigen::Vector3d(1, 1, -0.5 + kFloorLayerHeight));
  // Another method's graph: the same entities, empty.
  const auto none = sgraphEntities(Json::object(), formats::RosTime{});
  ASSERT_EQ(none.size(), 5u);
  EXPECT_TRUE((*entity(none, "sgraph/edges"))["lines"].empty());
}

TEST(RunScene, EachCandidatePlacesTheMapsWallsOnTheMatchedLevel) {
  const Json sgraph = Json::parse(R"({
    "planes": [{"id": 0, "floor": 0, "start": [0.0, 0.0], "end": [1.0, 0.0]},
               {"id": 1, "floor": 1, "start": [5.0, 5.0], "end": [6.0, 5.0]}],
    "matching": {"status": "matched", "level": "L1", "floor_levels": {"0": "L1", "1": "L2"},
                 "last_match": {"candidates": [
                   {"B_T_M": {"x": 1.0, "y": 2.0, "yaw": 1.5707963267948966}, "best": true,
                    "score": 10.04},
                   {"B_T_M": {"x": 0.0, "y": 0.0, "yaw": 0.0}, "score": 3.25}]}}
  })");
  const auto drawn = candidateEntities(sgraph, handAGraph(), formats::RosTime{});
  ASSERT_EQ(drawn.size(), 1u);
  const Json& e = drawn[0];
  EXPECT_EQ(e["frame_id"], "plan");
  ASSERT_EQ(e["lines"].size(), 2u);  // plane 1 is on another level
  // Turned 90° and moved by (1, 2), on L1's floor (3 m) lifted 0.1 m.
  const Json& best = e["lines"][0]["points"];
  ASSERT_EQ(best.size(), 2u);
  EXPECT_TRUE(point(best[0]).isApprox(Eigen::Vector3d(1, 2, 3.1), 1e-12));
  EXPECT_TRUE(point(best[1]).isApprox(Eigen::Vector3d(1, 3, 3.1), 1e-12));
  EXPECT_EQ(e["texts"][0]["text"], "best, score 10.0");
  EXPECT_EQ(e["texts"][1]["text"], "score 3.2");
  // No attempt yet: an empty entity, which clears the last one drawn.
  EXPECT_TRUE(
      candidateEntities(Json::object(), handAGraph(), formats::RosTime{})[0]["lines"].empty());
}

// A wall of the report by hand: planned from a to b on L1.
slam::WallDeviation wallOf(const std::string& id, slam::WallStatus status, double offset_m,
                           double angle_deg, Eigen::Vector2d a, Eigen::Vector2d b) {
  slam::WallDeviation wall;
  wall.wall = id;
  wall.level = "L1";
  wall.status = status;
  wall.offset_m = offset_m;
  wall.angle_deg = angle_deg;
  wall.planned_start = a;
  wall.planned_end = b;
  return wall;
}

TEST(RunScene, DeviationsAreColouredAndTheDeviatingOnesLabelled) {
  slam::DeviationReport deviations;
  deviations.walls.push_back(wallOf("W1", slam::WallStatus::kShifted, 0.312, 0.44, {0, 0}, {4, 0}));
  slam::WallEvidence evidence;
  evidence.start_B = {0, 0.3};
  evidence.end_B = {4, 0.3};
  deviations.walls.back().evidence.push_back(evidence);
  deviations.walls.push_back(wallOf("W2", slam::WallStatus::kAsPlanned, 0.01, 0.1, {4, 0}, {4, 4}));
  slam::ExtraWall extra;
  extra.level = "L1";
  extra.start = {1, 1};
  extra.end = {1, 3};
  deviations.extra_walls.push_back(extra);
  const auto drawn = deviationEntities(deviations, handAGraph(), formats::RosTime{});
  ASSERT_EQ(drawn.size(), 1u);
  const Json& walls = drawn[0];
  // W1 planned + its evidence, W2 planned, the extra wall.
  ASSERT_EQ(walls["lines"].size(), 4u);
  EXPECT_NEAR(walls["lines"][0]["points"][0]["z"].get<double>(), 3.05, 1e-12);
  EXPECT_GT(walls["lines"][0]["color"]["r"].get<double>(), 0.8);  // shifted: orange
  ASSERT_EQ(walls["texts"].size(), 1u);
  EXPECT_EQ(walls["texts"][0]["text"], "W1 shifted 0.31 m 0.4 deg");
  EXPECT_EQ(point(walls["lines"][3]["points"][1]), Eigen::Vector3d(1, 3, 3.05));
}

// A column of the report by hand, on L1.
slam::ColumnDeviation columnOf(const std::string& id, slam::ColumnStatus status,
                               Eigen::Vector2d centre, std::optional<Eigen::Vector2d> offset) {
  slam::ColumnDeviation column;
  column.column = id;
  column.level = "L1";
  column.status = status;
  column.planned_centre = centre;
  column.offset_m = offset;
  return column;
}

TEST(RunScene, ColumnsAreMarkedByStatusAndTheMovedOnesShowWhereTheyStand) {
  slam::DeviationReport deviations;
  deviations.columns = {
      columnOf("C1", slam::ColumnStatus::kAsPlanned, {2, 2}, Eigen::Vector2d(0.004, 0.0)),
      columnOf("C2", slam::ColumnStatus::kMoved, {6, 2}, Eigen::Vector2d(-0.12, 0.05)),
      columnOf("C3", slam::ColumnStatus::kMissing, {10, 2}, std::nullopt)};
  const auto drawn = deviationEntities(deviations, handAGraph(), formats::RosTime{});
  ASSERT_EQ(drawn.size(), 2u);
  const Json& columns = drawn[1];
  EXPECT_EQ(columns["id"], "deviations/columns");
  // A mark each, and the moved one's line to where the map found it: 0.13 m off.
  ASSERT_EQ(columns["lines"].size(), 4u);
  EXPECT_TRUE(
      point(columns["lines"][0]["points"][0]).isApprox(Eigen::Vector3d(1.75, 1.75, 3.07), 1e-12));
  EXPECT_GT(columns["lines"][0]["color"]["g"].get<double>(), 0.5);  // as planned: green
  EXPECT_TRUE(
      point(columns["lines"][2]["points"][1]).isApprox(Eigen::Vector3d(5.88, 2.05, 3.07), 1e-12));
  EXPECT_GT(columns["lines"][3]["color"]["r"].get<double>(), 0.8);  // missing: red
  ASSERT_EQ(columns["texts"].size(), 2u);                           // the moved and the missing one
  EXPECT_EQ(columns["texts"][0]["text"], "C2 moved 0.13 m");
  EXPECT_EQ(columns["texts"][1]["text"], "C3 missing");
}

TEST(RunScene, TheMapAgainstThePlanIsDrawnByHowFarOffEachStretchLies) {
  slam::DeviationReport deviations;
  slam::LevelAgainstPlan level;
  level.level = "L1";
  for (const auto& [from, mean] :
       std::vector<std::pair<double, double>>{{0.0, 0.004}, {1.0, -0.031}, {2.0, 0.12}}) {
    slam::FaceStretch stretch;
    stretch.start = {from, 0};
    stretch.end = {from + 1.0, 0};
    stretch.mean_m = mean;
    level.stretches.push_back(stretch);
  }
  deviations.against_plan.push_back(level);
  const auto drawn = deviationEntities(deviations, handAGraph(), formats::RosTime{});
  ASSERT_EQ(drawn.size(), 2u);
  const Json& against = drawn[1];
  EXPECT_EQ(against["id"], "deviations/map-against-plan");
  // One line list per class met (within 2 cm, 2–4 cm, beyond 8 cm), a metre above L1's floor.
  ASSERT_EQ(against["lines"].size(), 3u);
  EXPECT_EQ(point(against["lines"][0]["points"][1]), Eigen::Vector3d(1, 0, 4.0));
  EXPECT_EQ(point(against["lines"][2]["points"][0]), Eigen::Vector3d(2, 0, 4.0));
  ASSERT_EQ(against["texts"].size(), 1u);  // only the far one is labelled
  EXPECT_EQ(against["texts"][0]["text"], "0.12 m");
}

}  // namespace
}  // namespace isg::run
