#include "bim/column.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bim/facade.hpp"
#include "bim/plan_geometry.hpp"
#include "bim/plan_json.hpp"
#include "bim/plan_transform.hpp"
#include "bim/polygon.hpp"
#include "bim/tests/test_plans.hpp"

namespace isg::bim {
namespace {

using testing::columnHallPlanJson;
using testing::parsePlanJson;
using testing::planErrorOf;

TEST(Columns, AreReadWithTheirShapeSizeAndHeights) {
  const Plan plan = parsePlanJson(columnHallPlanJson());
  const Level& level = plan.levels[0];
  ASSERT_EQ(level.columns.size(), 5u);
  const Column& c1 = level.columns[0];
  EXPECT_FALSE(c1.round());
  EXPECT_EQ(c1.center, Eigen::Vector2d(3, 2));
  EXPECT_EQ(c1.size, Eigen::Vector2d(0.4, 0.3));
  EXPECT_EQ(c1.yaw, 0.0);
  EXPECT_EQ(c1.height, 3.0);  // the level's
  EXPECT_EQ(c1.base, 0.0);
  const Column& c4 = *level.findColumn("C4");
  EXPECT_TRUE(c4.round());
  EXPECT_EQ(c4.size, Eigen::Vector2d(0.5, 0.5));
  EXPECT_DOUBLE_EQ(c4.radius(), 0.25);
  EXPECT_EQ(c4.height, 2.6);
  EXPECT_EQ(c4.base, 0.1);
  EXPECT_EQ(c4.name, "tube");
  EXPECT_EQ(level.findColumn("W1"), nullptr);
}

TEST(Columns, AreWrittenBackAsRead) {
  const Plan plan = parsePlanJson(columnHallPlanJson());
  const auto written = planToJson(plan, {.every_wall_height = false});
  const auto& columns = written["levels"][0]["columns"];
  ASSERT_EQ(columns.size(), 5u);
  EXPECT_EQ(columns[0].dump(), R"({"id":"C1","center":[3.0,2.0],"size":[0.4,0.3]})");
  EXPECT_EQ(columns[2].dump(), R"({"id":"C3","center":[3.0,6.0],"diameter":0.4})");
  EXPECT_EQ(columns[3]["height"], 2.6);
  EXPECT_EQ(columns[3]["base"], 0.1);
  const Plan again = parsePlanJson(nlohmann::json::parse(written.dump()));
  ASSERT_EQ(again.levels[0].columns.size(), 5u);
  EXPECT_EQ(again.levels[0].columns[1].yaw, plan.levels[0].columns[1].yaw);
  // A plan without columns is written without the key, as before the extension.
  EXPECT_FALSE(
      planToJson(parsePlanJson(testing::twoRoomPlanJson()))["levels"][0].contains("columns"));
}

TEST(Columns, BadOnesAreRefusedNamingThePath) {
  auto doc = columnHallPlanJson();
  doc["levels"][0]["columns"][0]["diameter"] = 0.3;
  EXPECT_EQ(planErrorOf(doc),
            "test.json: /levels/0/columns/0/diameter: a column has a size or a diameter, not both");
  doc = columnHallPlanJson();
  doc["levels"][0]["columns"][0].erase("size");
  EXPECT_EQ(planErrorOf(doc),
            "test.json: /levels/0/columns/0: a column needs \"size\": [width, depth] "
            "(rectangular) or \"diameter\" (round)");
  doc = columnHallPlanJson();
  doc["levels"][0]["columns"][2]["yaw"] = 0.5;
  EXPECT_EQ(planErrorOf(doc), "test.json: /levels/0/columns/2/yaw: a round column has no yaw");
  doc = columnHallPlanJson();
  doc["levels"][0]["columns"][3]["base"] = 2.6;
  EXPECT_EQ(planErrorOf(doc),
            "test.json: /levels/0/columns/3/base: base 2.6 is not below the column's top at 2.6");
  doc = columnHallPlanJson();
  doc["levels"][0]["columns"][1]["id"] = "W2";
  EXPECT_NE(planErrorOf(doc).find("/levels/0/columns/1/id: duplicate id \"W2\""), std::string::npos)
      << planErrorOf(doc);
  doc = columnHallPlanJson();
  doc["levels"][0]["columns"][0]["size"] = {0.4};
  EXPECT_NE(planErrorOf(doc).find("/levels/0/columns/0/size"), std::string::npos)
      << planErrorOf(doc);
}

TEST(Columns, ALevelOfColumnsAloneNeedsNoWall) {
  auto doc = columnHallPlanJson();
  doc["levels"][0]["walls"] = nlohmann::json::array();
  const Plan plan = parsePlanJson(doc);
  EXPECT_TRUE(plan.levels[0].walls.empty());
  EXPECT_EQ(plan.levels[0].columns.size(), 5u);
  // Without columns either, a level still needs a wall.
  doc["levels"][0].erase("columns");
  EXPECT_NE(planErrorOf(doc).find("/levels/0/walls"), std::string::npos) << planErrorOf(doc);
}

TEST(Columns, FootprintsByHand) {
  const Plan plan = parsePlanJson(columnHallPlanJson());
  const Level& level = plan.levels[0];
  // C2: 0.4 along its own x, turned 90°: 0.3 wide in x, 0.4 deep in y about (9, 2).
  const auto c2 = columnFootprint(level.columns[1]);
  ASSERT_EQ(c2.size(), 4u);
  const Box2 box = Box2::around(c2);
  EXPECT_NEAR(box.lo.x(), 8.85, 1e-12);
  EXPECT_NEAR(box.hi.x(), 9.15, 1e-12);
  EXPECT_NEAR(box.lo.y(), 1.8, 1e-12);
  EXPECT_NEAR(box.hi.y(), 2.2, 1e-12);
  EXPECT_GT(signedArea(c2), 0.0);
  EXPECT_NEAR(signedArea(c2), 0.12, 1e-12);
  // C3: 24 sides touching the circle of radius 0.2 from outside: area 24 r² tan(π/24).
  const auto c3 = columnFootprint(level.columns[2]);
  ASSERT_EQ(c3.size(), 24u);
  EXPECT_NEAR(signedArea(c3), 24 * 0.04 * std::tan(std::numbers::pi / 24), 1e-12);
  for (std::size_t k = 0; k < c3.size(); ++k) {
    const Eigen::Vector2d mid = 0.5 * (c3[k] + c3[(k + 1) % c3.size()]);
    EXPECT_NEAR((mid - Eigen::Vector2d(3, 6)).norm(), 0.2, 1e-12);
  }
}

TEST(Columns, RectangularOnesHaveWallFacesAndRoundOnesHideWhatIsBehind) {
  const Plan plan = parsePlanJson(columnHallPlanJson());
  const Level& level = plan.levels[0];
  const LevelGeometry geometry = computeLevelGeometry(level);
  // The four walls, then C1 and C2 as walls of their width and depth.
  ASSERT_EQ(geometry.walls.size(), 6u);
  const WallGeometry& c1 = geometry.walls[4];
  EXPECT_EQ(c1.wall->id, "C1");
  EXPECT_NEAR(c1.length, 0.4, 1e-12);
  EXPECT_EQ(c1.wall->thickness, 0.3);
  // Its faces: y = 2 ± 0.15, 0.4 m long, the level's full height.
  EXPECT_NEAR(c1.left.plane.signedDistance({3, 2.15, 0}), 0.0, 1e-12);
  EXPECT_NEAR(c1.right.plane.signedDistance({3, 1.85, 0}), 0.0, 1e-12);
  ASSERT_EQ(c1.left.exposed.size(), 1u);
  EXPECT_NEAR(c1.left.exposed[0].length(), 0.4, 1e-12);
  EXPECT_EQ(c1.left.z_max, 3.0);
  const WallGeometry& c2 = geometry.walls[5];
  EXPECT_NEAR(std::abs(c2.axis.y()), 1.0, 1e-12);
  // Copies share the column walls: their pointers stay valid.
  const LevelGeometry copy = geometry;
  EXPECT_EQ(copy.walls[5].wall->id, "C2");
  // C5 (r 0.2 at y 0.25) reaches 0.15 m over the south wall's inner face y = 0.1: the face is
  // hidden over the chord 2 √(0.2² − 0.15²) = 0.265 m about x = 6 (a little more: the footprint
  // is the polygon round the circle).
  const WallFace& inner = geometry.walls[0].left;
  ASSERT_EQ(inner.exposed.size(), 2u);
  const double half_chord = std::sqrt(0.04 - 0.0225);
  EXPECT_NEAR(inner.exposed[0].hi, 6.0 - half_chord, 0.004);
  EXPECT_NEAR(inner.exposed[1].lo, 6.0 + half_chord, 0.004);
  EXPECT_LT(inner.exposed[0].hi, 6.0 - half_chord);
}

TEST(Columns, MakeTheFacadeOfAFloorOfColumns) {
  auto doc = columnHallPlanJson();
  doc["levels"][0]["walls"] = nlohmann::json::array();
  const Plan plan = parsePlanJson(doc);
  EXPECT_TRUE(isOpenFloor(plan.levels[0]));
  const Polygon2 hull = facadeOutline(plan.levels[0]);
  const Box2 box = Box2::around(hull);
  // From C3's west side (x = 2.8) to C4's east side (9.25), C5's south side (0.05) to C4's north
  // (6.25): round columns by their covering polygon, whose corners reach 1/cos(7.5°) = 1.0086
  // of the radius.
  EXPECT_NEAR(box.lo.x(), 3 - 0.2 / std::cos(std::numbers::pi / 24), 1e-9);
  EXPECT_NEAR(box.hi.x(), 9 + 0.25 / std::cos(std::numbers::pi / 24), 1e-9);
  EXPECT_NEAR(box.lo.y(), 0.25 - 0.2 / std::cos(std::numbers::pi / 24), 1e-9);
  EXPECT_NEAR(box.hi.y(), 6 + 0.25 / std::cos(std::numbers::pi / 24), 1e-9);
}

TEST(Columns, TurnWithThePlan) {
  const Plan plan = parsePlanJson(columnHallPlanJson());
  const Plan turned =
      transformedPlan(plan, planarMotion(Eigen::Vector2d(1, 0), std::numbers::pi / 2));
  const Column& c1 = turned.levels[0].columns[0];
  EXPECT_NEAR(c1.center.x(), 1 - 2, 1e-12);
  EXPECT_NEAR(c1.center.y(), 3, 1e-12);
  EXPECT_NEAR(c1.yaw, std::numbers::pi / 2, 1e-12);
  EXPECT_EQ(turned.levels[0].columns[2].yaw, 0.0);  // round: no yaw
}

}  // namespace
}  // namespace isg::bim
