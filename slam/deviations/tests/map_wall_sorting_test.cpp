// Each stage a map wall passes on its way into the report (map_wall_sorting.hpp), by hand on small
// plans: the two-room plan (W2's inner face x = 5.9 from y = 0.1 to 3.9, looking to −x), the
// column hall (C1 a 0.4 m × 0.3 m rectangle at (3, 2)), and two walls in line with a gap.
#include "slam/deviations/map_wall_sorting.hpp"

#include <gtest/gtest.h>

#include "bim/tests/test_plans.hpp"

namespace isg::slam {
namespace {

WallInB mapWall(Eigen::Vector2d start, Eigen::Vector2d end, Eigen::Vector2d normal,
                int observations = 5) {
  WallInB m;
  m.start = start;
  m.end = end;
  m.normal = normal.normalized();
  m.z_min = 0.1;
  m.z_max = 2.6;
  m.observations = observations;
  return m;
}

bim::AGraph agraphOf(const nlohmann::json& plan) {
  return bim::buildAGraph(bim::testing::parsePlanJson(plan));
}

TEST(MapWallSorting, AWallAlongAFaceIsItsEvidence) {
  const bim::AGraph plan = agraphOf(bim::testing::twoRoomPlanJson());
  const DeviationOptions options;
  const WallInB m = mapWall({5.92, 0.5}, {5.92, 3.5}, {-1, 0});
  const SortedMapWall sorted = sortMapWall(plan, "L0", m, options);
  EXPECT_EQ(sorted.role, MapWallRole::kEvidence);
  ASSERT_GE(sorted.surface, 0);
  EXPECT_EQ(plan.surfaces[sorted.surface].id, "W2:left");
  // Facing the other way it is the outer face's (x = 6.1, 18 cm off); turned 30° from the face
  // (beyond the 20° search angle), or on another level, it is none's.
  EXPECT_EQ(
      plan.surfaces[surfaceOf(plan, "L0", mapWall({5.92, 0.5}, {5.92, 3.5}, {1, 0}), options)].id,
      "W2:right");
  EXPECT_EQ(surfaceOf(plan, "L0", mapWall({5.92, 0.5}, {5.92, 3.5}, {-0.866, 0.5}), options), -1);
  EXPECT_EQ(surfaceOf(plan, "L1", m, options), -1);
  // Past the face, over less than a third of it along the face: an extra wall in line with it.
  const WallInB past = mapWall({5.92, 2.5}, {5.92, 8.5}, {-1, 0});
  EXPECT_EQ(surfaceOf(plan, "L0", past, options), -1);
  EXPECT_TRUE(piecesAlongFaces(plan, "L0", past, options).empty());
  EXPECT_EQ(sortMapWall(plan, "L0", past, options).role, MapWallRole::kUnexplained);
}

TEST(MapWallSorting, AWallAlongTwoFacesInLineIsEvidenceForEachByItsPiece) {
  const bim::AGraph plan = agraphOf(nlohmann::json::parse(R"({
    "format": "isg.plan", "version": 1, "name": "two walls in line",
    "levels": [{"id": "L0", "height": 3.0, "walls": [
      {"id": "A", "start": [0, 0], "end": [4, 0], "thickness": 0.2},
      {"id": "B", "start": [5, 0], "end": [9, 0], "thickness": 0.2}]}]
  })"));
  const WallInB m = mapWall({0.0, 0.1}, {9.0, 0.1}, {0, 1});
  const SortedMapWall sorted = sortMapWall(plan, "L0", m, DeviationOptions{});
  ASSERT_EQ(sorted.role, MapWallRole::kAlongFacesInLine);
  ASSERT_EQ(sorted.pieces.size(), 2u);
  for (const auto& [surface, piece] : sorted.pieces) {
    const bool a = plan.surfaces[surface].id == "A:left";
    EXPECT_TRUE(a || plan.surfaces[surface].id == "B:left") << plan.surfaces[surface].id;
    // Each piece is the part of the map wall along its face's extent.
    EXPECT_NEAR(piece.start.x(), a ? 0.0 : 5.0, 1e-9);
    EXPECT_NEAR(piece.end.x(), a ? 4.0 : 9.0, 1e-9);
  }
}

TEST(MapWallSorting, AWallAllAlongAColumnIsTheColumns) {
  const bim::AGraph plan = agraphOf(bim::testing::columnHallPlanJson());
  const DeviationOptions options;
  // C1's east end, x = 3.2 from y = 1.85 to 2.15: the A-Graph holds no surface for it.
  const WallInB end = mapWall({3.22, 1.85}, {3.22, 2.15}, {1, 0});
  EXPECT_TRUE(onColumn(plan, "L0", end, options));
  EXPECT_EQ(sortMapWall(plan, "L0", end, options).role, MapWallRole::kOnColumn);
  // 0.4 m clear of it (column_margin 0.35), it is not.
  EXPECT_FALSE(onColumn(plan, "L0", mapWall({3.6, 1.85}, {3.6, 2.15}, {1, 0}), options));
}

TEST(MapWallSorting, AWallSeenLittleLeaningOrOnlyThroughWallsIsAStrayFit) {
  const bim::AGraph plan = agraphOf(bim::testing::twoRoomPlanJson());
  const DeviationOptions options;  // fewer than 3 observations, a lean of over 1°
  WallInB m = mapWall({4.5, 0.8}, {4.5, 2.8}, {1, 0}, 2);
  EXPECT_EQ(sortMapWall(plan, "L0", m, options).role, MapWallRole::kUnexplained);
  m.lean_deg = 1.2;
  EXPECT_EQ(sortMapWall(plan, "L0", m, options).role, MapWallRole::kStray);
  m.observations = 3;  // seen often enough: a wall the plan lacks, leaning or not
  EXPECT_EQ(sortMapWall(plan, "L0", m, options).role, MapWallRole::kUnexplained);
  m.lean_deg = 0.0;
  m.observations = 1;
  m.behind_walls = true;
  EXPECT_TRUE(isStray(m, options));
  EXPECT_EQ(sortMapWall(plan, "L0", m, options).role, MapWallRole::kStray);
}

}  // namespace
}  // namespace isg::slam
