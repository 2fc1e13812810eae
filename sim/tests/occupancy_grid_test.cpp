#include "sim/occupancy_grid.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>

#include "bim/plan_geometry.hpp"
#include "sim/route_planner.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

// A wall shifted as built carries its doorways with it, and the strip of its planned footprint it
// left is floor: the doorway stays open whichever way the wall moved and by however much a
// scenario may shift it. (The grid once kept that strip blocked: a shift wider than a cell shut
// every door of the wall.)
TEST(OccupancyGrid, AShiftedWallKeepsItsDoorwaysOpen) {
  const bim::Scenario scenario = worlds::loadScenarioOrBuiltin("builtin:d1", nullptr);
  const bim::Plan& plan = scenario.plan;
  const bim::Level& level = plan.levels.at(0);
  const bim::Door* door = nullptr;
  for (const auto& d : level.doors) {
    if (d.rooms[0] != bim::kOutside && d.rooms[1] != bim::kOutside) {
      door = &d;
      break;
    }
  }
  ASSERT_NE(door, nullptr);
  const bim::LevelGeometry planned = bim::computeLevelGeometry(level);
  const bim::WallGeometry& wall = *planned.findWall(door->wall);
  const Eigen::Vector2d centre = wall.pointAt(door->offset);
  const bim::Room* a = level.findRoom(door->rooms[0]);
  const bim::Room* b = level.findRoom(door->rooms[1]);
  for (const double offset : {-0.12, -0.08, -0.03, 0.03, 0.08, 0.12}) {
    bim::AsBuilt as_built;
    as_built.wall_shifts.push_back({door->wall, offset});
    const OccupancyGrid grid(plan, as_built, level.id);
    // Across the doorway, from 0.3 m before the planned wall to 0.3 m beyond it, the robot keeps
    // its clearance: half the 0.9 m door less the cell's diagonal (0.07 m) is more than 0.35 m.
    for (double s = -0.3; s <= 0.3; s += 0.01) {
      const Eigen::Vector2d p = centre + s * wall.left_normal;
      EXPECT_GE(grid.clearanceAt(p), kMinClearance) << "shift " << offset << ", s " << s;
    }
    // Beside the doorway, the wall stands where it was moved to, and no longer where it was.
    const Eigen::Vector2d beside = centre + (0.5 * door->width + 0.3) * wall.axis;
    EXPECT_TRUE(grid.blocked(grid.cellOf(beside + offset * wall.left_normal)));
    if (std::abs(offset) >= 0.08) {
      // The vacated strip: the planned face on the side the wall moved away from.
      const double side = offset > 0 ? -1.0 : 1.0;
      const Eigen::Vector2d vacated =
          beside + side * (0.5 * wall.wall->thickness - 0.02) * wall.left_normal;
      EXPECT_FALSE(grid.blocked(grid.cellOf(vacated))) << "shift " << offset;
    }
    ASSERT_NE(a, nullptr);
    ASSERT_NE(b, nullptr);
    EXPECT_FALSE(findPath(grid, roomGoal(grid, *a), roomGoal(grid, *b)).empty())
        << "shift " << offset;
  }
}

// A level as large as an L of 1000 offices (175 × 175 m: 12.3 M cells of 5 cm) keeps 5 cm cells,
// and its doorways keep the robot's clearance; only a level past OccupancyGrid::kMaxCells cells
// gets coarser ones, exactly as many as the budget allows. (At 8 M cells such an L got 6.1 cm
// cells, which shut 167 of its doorways.)
TEST(OccupancyGrid, ALargeLevelKeepsFiveCentimetreCellsUpToItsBudget) {
  bim::Scenario scenario = worlds::loadScenarioOrBuiltin("builtin:d1", nullptr);
  bim::Level& level = scenario.plan.levels.at(0);
  const bim::Door* door = nullptr;
  for (const auto& d : level.doors) {
    if (d.rooms[0] != bim::kOutside && d.rooms[1] != bim::kOutside) door = &d;
  }
  ASSERT_NE(door, nullptr);
  const bim::Door inner = *door;
  const bim::WallGeometry wall = *bim::computeLevelGeometry(level).findWall(inner.wall);
  Eigen::Vector2d lo = level.walls.at(0).start;  // the level's walls' lowest corner
  for (const auto& w : level.walls) lo = lo.cwiseMin(w.start).cwiseMin(w.end);
  for (const double side : {175.0, 300.0}) {
    bim::Level large = level;
    // A short wall far off stretches the level's box to side × side metres.
    const Eigen::Vector2d far = lo + Eigen::Vector2d::Constant(side);
    large.walls.push_back({"far", far - Eigen::Vector2d(1, 0), far, 0.2, 3.0, 0.0, ""});
    bim::Plan plan = scenario.plan;
    plan.levels.at(0) = large;
    const OccupancyGrid grid(plan, scenario.as_built, large.id);
    const double cells = double(grid.width()) * grid.height();
    if (side == 175.0) {
      EXPECT_DOUBLE_EQ(grid.resolution(), 0.05);
      EXPECT_GT(cells, 8e6);  // past the old budget
      const Eigen::Vector2d centre = wall.pointAt(inner.offset);
      for (double s = -0.3; s <= 0.3; s += 0.01) {
        EXPECT_GE(grid.clearanceAt(centre + s * wall.left_normal), kMinClearance) << s;
      }
    } else {
      EXPECT_GT(grid.resolution(), 0.05);
      EXPECT_NEAR(cells, OccupancyGrid::kMaxCells, 0.01 * OccupancyGrid::kMaxCells);
      // The route keeps the coarse level's cell size, for a message about rooms it cannot reach.
      bim::Scenario large_scenario = scenario;
      large_scenario.plan = plan;
      std::mt19937_64 rng(1);
      const PlannedRoute route = planRoute(large_scenario, grid, rng);
      EXPECT_EQ(route.coarse_cells, (std::map<std::string, double>{{large.id, grid.resolution()}}));
    }
  }
}

}  // namespace
}  // namespace isg::sim
