#include "bim/plan_transform.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "bim/plan_geometry.hpp"
#include "bim/polygon.hpp"
#include "bim/tests/test_plans.hpp"

namespace isg::bim {
namespace {

constexpr double kQuarterTurn = std::numbers::pi / 2.0;

TEST(PlanTransform, WallsAndOutlinesMoveDoorsAndHeightsStay) {
  const Plan plan = testing::parsePlanJson(testing::twoRoomPlanJson());
  // A quarter turn about B's origin, then 8 km east: (x, y) → (8000 − y, x).
  const Plan moved = transformedPlan(plan, planarMotion({8000.0, 0.0}, kQuarterTurn));
  const Level& level = moved.levels[0];
  const Wall& w1 = *level.findWall("W1");  // (0, 0) → (6, 0)
  EXPECT_NEAR((w1.start - Eigen::Vector2d(8000.0, 0.0)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((w1.end - Eigen::Vector2d(8000.0, 6.0)).norm(), 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(level.findWall("W5")->height, 2.8);
  EXPECT_DOUBLE_EQ(level.findDoor("D2")->offset, 4.5);
  // R1's corner (2.95, 3.9) → (7996.1, 2.95); the outline stays counter-clockwise, same area.
  const Room& r1 = *level.findRoom("R1");
  EXPECT_NEAR((r1.outline[2] - Eigen::Vector2d(7996.1, 2.95)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(signedArea(r1.outline), 2.85 * 3.8, 1e-6);
  // The moved level is the same building: the same room behind each door.
  EXPECT_EQ(roomAt(level, Eigen::Vector2d(8000.0 - 2.0, 1.5)), std::optional<std::string>("R1"));
}

TEST(PlanTransform, PosesTurnWithTheBuildingAndWhatIsAlongAWallStays) {
  Scenario scenario;
  scenario.plan = testing::parsePlanJson(testing::twoRoomPlanJson());
  scenario.robot.start_pose = Eigen::Vector3d(1.0, 2.0, 0.5);
  scenario.robot.route.waypoints = {{4.0, 1.0}};
  scenario.robot.kidnap.push_back({10.0, std::nullopt, Eigen::Vector3d(5.0, 3.0, -3.0), "L0"});
  ExtraWall extra;
  extra.start = {1.0, 1.0};
  extra.end = {2.0, 1.0};
  scenario.as_built.extra_walls.push_back(extra);
  scenario.as_built.clutter.push_back({"L0", {1.0, 3.0, 0.4}, {0.5, 0.5, 0.8}, 3.0});
  scenario.as_built.wall_shifts.push_back({"W5", 0.05});
  const Eigen::Isometry2d T = planarMotion({10.0, 0.0}, kQuarterTurn);  // (x, y) → (10 − y, x)
  const Scenario moved = transformedScenario(scenario, T);
  EXPECT_NEAR((*moved.robot.start_pose - Eigen::Vector3d(8.0, 1.0, 0.5 + kQuarterTurn)).norm(), 0,
              1e-12);
  EXPECT_NEAR((moved.robot.route.waypoints[0] - Eigen::Vector2d(9.0, 4.0)).norm(), 0, 1e-12);
  // −3 + π/2 is −1.429: within (−π, π] already.
  EXPECT_NEAR((*moved.robot.kidnap[0].pose - Eigen::Vector3d(7.0, 5.0, -3.0 + kQuarterTurn)).norm(),
              0, 1e-12);
  EXPECT_NEAR((moved.as_built.extra_walls[0].end - Eigen::Vector2d(9.0, 2.0)).norm(), 0, 1e-12);
  // The clutter's centre keeps its height; its yaw 3 + π/2 wraps to 3 + π/2 − 2π.
  EXPECT_NEAR((moved.as_built.clutter[0].center - Eigen::Vector3d(7.0, 1.0, 0.4)).norm(), 0, 1e-12);
  EXPECT_NEAR(moved.as_built.clutter[0].yaw, 3.0 + kQuarterTurn - 2.0 * std::numbers::pi, 1e-12);
  EXPECT_DOUBLE_EQ(moved.as_built.wall_shifts[0].offset, 0.05);
  // And back: the inverse motion gives the scenario we started from.
  const Scenario back = transformedScenario(moved, T.inverse());
  EXPECT_NEAR((*back.robot.start_pose - *scenario.robot.start_pose).norm(), 0.0, 1e-12);
  EXPECT_NEAR((back.plan.levels[0].walls[2].end - scenario.plan.levels[0].walls[2].end).norm(), 0.0,
              1e-12);
}

}  // namespace
}  // namespace isg::bim
