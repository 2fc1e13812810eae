#include "worlds/as_built.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "bim/as_built_wall.hpp"
#include "bim/tests/test_plans.hpp"

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

// Columns as built: one not built, one moved; the rest as planned.
TEST(AsBuiltLevel, ColumnsMissingOrMoved) {
  const bim::Plan plan = bim::testing::parsePlanJson(bim::testing::columnHallPlanJson());
  bim::AsBuilt as_built;
  as_built.missing_columns = {"C4"};
  as_built.moved_columns = {{"C1", Eigen::Vector2d(0.15, -0.1)}};
  const bim::Level built = asBuiltLevel(plan.levels[0], as_built);
  EXPECT_EQ(built.columns.size(), plan.levels[0].columns.size() - 1);
  EXPECT_EQ(built.findColumn("C4"), nullptr);
  EXPECT_EQ(built.findColumn("C1")->center, Eigen::Vector2d(3.15, 1.9));
  EXPECT_EQ(built.findColumn("C2")->center, Eigen::Vector2d(9, 2));
  EXPECT_FALSE(as_built.empty());
}

// Turned by hand: W5 runs (0, 4) → (20, 4) with door(s) placed along it from its start.
TEST(AsBuiltLevel, TurnsAWallAboutItsStartCentreOrEnd) {
  const bim::Scenario s = loadScenarioOrBuiltin("builtin:d3", nullptr);
  const bim::Level& plan_level = s.plan.levels[0];
  auto turned = [&](double angle_deg, bim::WallRotation::About about) {
    bim::AsBuilt as_built;
    as_built.wall_rotations = {{"W5", angle_deg, about}};
    return *asBuiltLevel(plan_level, as_built).findWall("W5");
  };
  const bim::Wall at_start = turned(90.0, bim::WallRotation::About::kStart);
  EXPECT_TRUE(at_start.start.isApprox(Eigen::Vector2d(0, 4)));
  EXPECT_TRUE(at_start.end.isApprox(Eigen::Vector2d(0, 24)));
  const bim::Wall at_centre = turned(90.0, bim::WallRotation::About::kCentre);
  EXPECT_TRUE(at_centre.start.isApprox(Eigen::Vector2d(10, -6)));
  EXPECT_TRUE(at_centre.end.isApprox(Eigen::Vector2d(10, 14)));
  const bim::Wall at_end = turned(-90.0, bim::WallRotation::About::kEnd);
  EXPECT_TRUE(at_end.start.isApprox(Eigen::Vector2d(20, 24)));
  EXPECT_TRUE(at_end.end.isApprox(Eigen::Vector2d(20, 4)));
  // Turned and shifted: turned first, then moved along the planned left normal (+y).
  bim::AsBuilt both;
  both.wall_rotations = {{"W5", 90.0, bim::WallRotation::About::kStart}};
  both.wall_shifts = {{"W5", 0.5}};
  EXPECT_TRUE(
      asBuiltLevel(plan_level, both).findWall("W5")->start.isApprox(Eigen::Vector2d(0, 4.5)));
}

// D3's W6 runs (0, 6) → (20, 6) with doors D1–D4 at 2, 7, 12.5 and 17.5 m along it.
TEST(AsBuiltLevel, AWallBuiltInPartStandsAsItsPartsWithTheirDoors) {
  const bim::Scenario s = loadScenarioOrBuiltin("builtin:d3", nullptr);
  const bim::Level& plan_level = s.plan.levels[0];
  bim::AsBuilt as_built;
  as_built.shortened_walls = {{"W6", {{0.0, 9.0}, {14.0, 20.0}}}};
  const bim::Level built = asBuiltLevel(plan_level, as_built);
  EXPECT_EQ(built.findWall("W6"), nullptr);
  ASSERT_NE(built.findWall("W6#1"), nullptr);
  ASSERT_NE(built.findWall("W6#2"), nullptr);
  EXPECT_EQ(built.walls.size(), plan_level.walls.size() + 1);
  EXPECT_EQ(built.findWall("W6#1")->start, Eigen::Vector2d(0, 6));
  EXPECT_EQ(built.findWall("W6#1")->end, Eigen::Vector2d(9, 6));
  EXPECT_EQ(built.findWall("W6#2")->start, Eigen::Vector2d(14, 6));
  EXPECT_EQ(built.findWall("W6#2")->end, Eigen::Vector2d(20, 6));
  EXPECT_DOUBLE_EQ(built.findWall("W6#2")->thickness, 0.2);
  // D1 and D2 in the first part where they were, D4 3.5 m along the second, D3 gone with the gap.
  EXPECT_EQ(built.findDoor("D1")->wall, "W6#1");
  EXPECT_DOUBLE_EQ(built.findDoor("D2")->offset, 7.0);
  EXPECT_EQ(built.findDoor("D4")->wall, "W6#2");
  EXPECT_DOUBLE_EQ(built.findDoor("D4")->offset, 3.5);
  EXPECT_EQ(built.findDoor("D3"), nullptr);
  EXPECT_EQ(built.doors.size(), plan_level.doors.size() - 1);
  // Shifted as well: the parts stand along the wall as built.
  as_built.wall_shifts = {{"W6", 0.5}};
  EXPECT_EQ(asBuiltLevel(plan_level, as_built).findWall("W6#2")->start, Eigen::Vector2d(14, 6.5));
}

// The deviation of a built axis, as the deviation report measures it, by hand.
TEST(AsBuiltLevel, AxisDeviationAtThePlannedCentre) {
  bim::Wall planned;
  planned.start = {0, 0};
  planned.end = {4, 0};
  // Parallel, 0.3 m to the left: the same offset anywhere, whichever way it points.
  bim::AxisDeviation d = bim::axisDeviation(planned, {7, 0.3}, {-1, 0});
  EXPECT_NEAR(d.offset_m, 0.3, 1e-12);
  EXPECT_NEAR(d.angle_deg, 0.0, 1e-12);
  // Turned 5° about the planned start: at the centre (x = 2) it stands 2·tan 5° to the left.
  const double a = 5.0 * M_PI / 180.0;
  d = bim::axisDeviation(planned, {0, 0}, {std::cos(a), std::sin(a)});
  EXPECT_NEAR(d.offset_m, 2.0 * std::tan(a), 1e-12);
  EXPECT_NEAR(d.angle_deg, 5.0, 1e-12);
  // The built wall from a scenario agrees: turned −3° about its end, then shifted −0.1 m.
  bim::AsBuilt as_built;
  planned.id = "W";
  as_built.wall_rotations = {{"W", -3.0, bim::WallRotation::About::kEnd}};
  as_built.wall_shifts = {{"W", -0.1}};
  const bim::Wall built = bim::builtWall(planned, as_built);
  d = bim::axisDeviation(planned, built.start, built.end - built.start);
  EXPECT_NEAR(d.angle_deg, -3.0, 1e-12);
  EXPECT_NEAR(d.offset_m, -0.1 + 2.0 * std::tan(3.0 * M_PI / 180.0), 1e-12);
}

}  // namespace
}  // namespace isg::worlds
