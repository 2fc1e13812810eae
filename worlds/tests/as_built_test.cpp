#include "worlds/as_built.hpp"

#include <gtest/gtest.h>

#include "worlds/reference_plans.hpp"

namespace isg::worlds {
namespace {

TEST(AsBuiltLevel, AppliesEveryDeviation) {
  const bim::Scenario s = loadScenarioOrBuiltin("builtin:d3", nullptr);
  bim::AsBuilt as_built;
  as_built.missing_walls = {"W7"};        // holds no door
  as_built.wall_shifts = {{"W5", -0.1}};  // (0, 4) → (20, 4): left is +y, so it moves to y = 3.9
  bim::ExtraWall extra;
  extra.id = "extra0";
  extra.level = "L0";
  extra.start = {1, 1};
  extra.end = {2, 1};
  as_built.extra_walls = {extra};
  const bim::Level& plan_level = s.plan.levels[0];
  const bim::Level built = asBuiltLevel(plan_level, as_built);
  EXPECT_EQ(built.walls.size(), plan_level.walls.size());  // one gone, one added
  EXPECT_EQ(built.findWall("W7"), nullptr);
  EXPECT_EQ(built.findWall("W5")->start, Eigen::Vector2d(0, 3.9));
  EXPECT_EQ(built.findWall("W5")->end, Eigen::Vector2d(20, 3.9));
  ASSERT_NE(built.findWall("extra0"), nullptr);
  EXPECT_DOUBLE_EQ(built.findWall("extra0")->height, plan_level.height);
  EXPECT_EQ(built.doors.size(), plan_level.doors.size());

  as_built.missing_walls = {"W6"};  // the corridor's north wall, with four doors
  EXPECT_EQ(asBuiltLevel(plan_level, as_built).doors.size(), plan_level.doors.size() - 4);
}

}  // namespace
}  // namespace isg::worlds
