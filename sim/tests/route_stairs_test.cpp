// Routes over several storeys (builtin:storeys: L0 and L1 joined by flight S1 in the corridor,
// from (9, 0.85) on L0 up to (13.5, 0.85) on L1).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/input_error.hpp"
#include "sim/occupancy_grid.hpp"
#include "sim/route_planner.hpp"
#include "sim/simulation.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

bim::Scenario storeys() {
  return worlds::loadScenarioOrBuiltin("builtin:storeys.asbuilt", nullptr);
}

PlannedRoute plan(const bim::Scenario& scenario) {
  const OccupancyGrid grid(scenario.plan, scenario.as_built, scenario.robot.level);
  std::mt19937_64 rng(1);
  return planRoute(scenario, grid, rng);
}

TEST(StairsRoute, TheTourClimbsTheFlightAndToursTheFloorAbove) {
  const PlannedRoute route = plan(storeys());
  EXPECT_EQ(route.visited_rooms,
            (std::vector<std::string>{"R4", "R1", "R2", "R3", "R14", "R11", "R12", "R13"}));
  EXPECT_TRUE(route.skipped_rooms.empty());
  EXPECT_TRUE(route.skipped_levels.empty());
  ASSERT_EQ(route.waypoint_levels.size(), route.waypoints.size());
  // One change of level, at the flight: its bottom edge on L0, its top edge on L1, walked
  // straight along its axis from an approach point before it to one beyond it.
  int changes = 0;
  for (std::size_t i = 1; i < route.waypoints.size(); ++i) {
    if (route.waypoint_levels[i] == route.waypoint_levels[i - 1]) continue;
    ++changes;
    EXPECT_EQ(route.waypoint_levels[i - 1], "L0");
    EXPECT_EQ(route.waypoint_levels[i], "L1");
    EXPECT_TRUE(route.waypoints[i - 1].isApprox(Eigen::Vector2d(9, 0.85)));
    EXPECT_TRUE(route.waypoints[i].isApprox(Eigen::Vector2d(13.5, 0.85)));
    EXPECT_NEAR(route.waypoints[i - 2].y(), 0.85, 1e-9);
    EXPECT_LT(route.waypoints[i - 2].x(), 9.0 - 0.35);
    EXPECT_NEAR(route.waypoints[i + 1].y(), 0.85, 1e-9);
    EXPECT_GT(route.waypoints[i + 1].x(), 13.5 + 0.35);
  }
  EXPECT_EQ(changes, 1);
}

TEST(StairsRoute, TheTourGoesDownAndComesBackUpForTheFloorAbove) {
  // builtin:twin-storeys starts on L1; S1 joins L0 and L1, S2 L1 and L2. Flights in plan order:
  // down S1 to tour L0, back up S1 (L1 still has S2 to a level not toured), up S2 to L2.
  const PlannedRoute route =
      plan(worlds::loadScenarioOrBuiltin("builtin:twin-storeys.asbuilt", nullptr));
  EXPECT_EQ(route.visited_rooms, (std::vector<std::string>{"R14", "R11", "R12", "R13", "R03", "R01",
                                                           "R02", "R24", "R21", "R22", "R23"}));
  std::vector<std::string> levels{route.waypoint_levels.front()};
  for (const auto& l : route.waypoint_levels) {
    if (l != levels.back()) levels.push_back(l);
  }
  EXPECT_EQ(levels, (std::vector<std::string>{"L1", "L0", "L1", "L2"}));
  EXPECT_TRUE(route.skipped_rooms.empty());
}

TEST(StairsRoute, NoPathOnOneLevelCrossesAFlightOrItsStairwell) {
  const bim::Scenario scenario = storeys();
  const PlannedRoute route = plan(scenario);
  for (std::size_t i = 1; i < route.waypoints.size(); ++i) {
    if (route.waypoint_levels[i] != route.waypoint_levels[i - 1]) continue;
    const Eigen::Vector2d a = route.waypoints[i - 1], b = route.waypoints[i];
    // Segments on a level either lead to or from a flight's edge along its axis, or stay clear
    // of its steps on L0 (x in [9, 13.5], y in [0.35, 1.35]) and of the stairwell on L1: the
    // part of the flight rising within 2 m of L1's floor, 4.5 × 2 / 3.2 = 2.8125 m from its top.
    if (std::abs(a.y() - 0.85) < 1e-9 && std::abs(b.y() - 0.85) < 1e-9) continue;
    const double x0 = route.waypoint_levels[i] == "L0" ? 9.0 : 13.5 - 2.8125;
    for (double u = 0; u <= 1.0; u += 0.01) {
      const Eigen::Vector2d p = a + u * (b - a);
      EXPECT_FALSE(p.x() > x0 && p.x() < 13.5 && p.y() > 0.35 && p.y() < 1.35)
          << "segment " << i << " on " << route.waypoint_levels[i];
    }
  }
}

// Rooms left out on a level whose route grid is coarser than asked are said with its cell size,
// the likely cause (a level past OccupancyGrid::kMaxCells cells of 5 cm).
TEST(StairsRoute, RoomsLeftOutOnACoarseGridSayItsCellSize) {
  PlannedRoute route;
  route.coarse_cells = {{"L0", 0.0608}};
  EXPECT_EQ(coarseCellsNote(route), "");  // every room reached
  route.skipped_rooms = {"R4", "R13"};
  EXPECT_EQ(unreachedPart(route) + coarseCellsNote(route),
            "rooms R4, R13 (the route grid of level \"L0\" (6.1 cm) has coarser cells than asked, "
            "the level being too large for 24 M of them: a doorway much under 1 m wide can be shut "
            "at that size)");
}

// A flight the tour cannot take (a crate across the corridor before its foot) leaves its level
// out: listed in skipped_levels with the reason, never toured-around in silence.
TEST(StairsRoute, ALevelTheTourCannotReachIsSkippedAndSaysWhy) {
  bim::Scenario scenario = storeys();
  bim::Clutter crate;
  crate.level = "L0";
  crate.center = Eigen::Vector3d(7.6, 0.85, 0.4);
  crate.size = Eigen::Vector3d(2.6, 1.0, 0.8);
  scenario.as_built.clutter.push_back(crate);
  const PlannedRoute route = plan(scenario);
  EXPECT_EQ(route.visited_rooms, (std::vector<std::string>{"R4", "R1", "R2", "R3"}));
  EXPECT_EQ(route.skipped_levels, (std::vector<std::string>{"L1"}));
  EXPECT_EQ(unreachedPart(route), "level L1");
  EXPECT_EQ(unreachedPart(plan(storeys())), "");
  EXPECT_EQ(coarseCellsNote(route), "");  // no room left out, and no coarse grid
  ASSERT_EQ(route.why_levels_skipped.count("L1"), 1u);
  EXPECT_EQ(route.why_levels_skipped.at("L1").rfind("flight \"S1\" cannot be reached from (", 0),
            0u)
      << route.why_levels_skipped.at("L1");
  EXPECT_NE(route.why_levels_skipped.at("L1").find(
                ") or stepped off, keeping 0.35 m from walls and clutter"),
            std::string::npos);
  // Without the flight: no flight leads there.
  scenario.plan.levels[0].stairs.clear();
  const PlannedRoute without = plan(scenario);
  EXPECT_EQ(without.skipped_levels, (std::vector<std::string>{"L1"}));
  EXPECT_EQ(without.why_levels_skipped.at("L1"),
            "no flight of stairs leads to it from the levels toured");
}

TEST(StairsRoute, RoomsOnOtherLevelsAreReachedByTheFlight) {
  bim::Scenario scenario = storeys();
  scenario.robot.route.kind = bim::Route::Kind::kRooms;
  scenario.robot.route.rooms = {"R13", "R2"};
  const PlannedRoute route = plan(scenario);
  EXPECT_EQ(route.visited_rooms, (std::vector<std::string>{"R4", "R13", "R2"}));
  int changes = 0;
  for (std::size_t i = 1; i < route.waypoints.size(); ++i) {
    changes += route.waypoint_levels[i] != route.waypoint_levels[i - 1];
  }
  EXPECT_EQ(changes, 2);  // up and down again
  EXPECT_EQ(route.targets.back().level, "L0");
  EXPECT_EQ(route.targets[1].level, "L1");
  // Without the flight the room above cannot be reached, and the error says why.
  scenario.plan.levels[0].stairs.clear();
  try {
    plan(scenario);
    FAIL() << "expected an InputError";
  } catch (const common::InputError& e) {
    EXPECT_EQ(e.pointer(), "/robot/route/rooms/0");
    EXPECT_EQ(e.reason(),
              "room \"R13\" is on level \"L1\", which no flight of stairs leads to from level "
              "\"L0\"");
  }
}

TEST(StairsRoute, TheRobotClimbsInTheSimulation) {
  const Simulation sim(storeys());
  const BaseMotion& motion = sim.baseMotion();
  // Ends on the first floor, 3.2 m up, standing 0.46 m above it.
  EXPECT_NEAR(motion.pose(motion.duration()).translation().z(), 3.2 + 0.46, 1e-9);
  EXPECT_NEAR(motion.pose(0.0).translation().z(), 0.46, 1e-9);
}

// A kidnap may put the robot down on another level: the ground truth jumps up a storey, the
// odometry does not, and the tour goes on with the rooms it had not reached, down the flight to
// those left below and back up for those above.
TEST(StairsRoute, AKidnapToARoomAboveGoesOnByTheFlight) {
  bim::Scenario scenario = storeys();
  const Simulation plain(scenario);
  const auto& targets = plain.route().targets;
  ASSERT_GE(targets.size(), 2u);
  ASSERT_EQ(targets[1].room, "R1");
  const double when = plain.baseMotion().arrival(0, targets[1].waypoint) + 1.0;
  scenario.robot.kidnap.push_back({when, "R12", std::nullopt, "L1"});
  const Simulation sim(scenario);
  const PlannedRoute& route = sim.route();
  EXPECT_EQ(route.visited_rooms,
            (std::vector<std::string>{"R4", "R1", "R12", "R2", "R3", "R14", "R11", "R13"}));
  EXPECT_TRUE(route.skipped_rooms.empty());
  ASSERT_EQ(route.kidnaps.size(), 1u);
  const KidnapLeg& leg = route.kidnaps[0];
  ASSERT_EQ(leg.waypoint_levels.size(), leg.waypoints.size());
  std::vector<std::string> levels{leg.waypoint_levels.front()};
  for (const auto& l : leg.waypoint_levels) {
    if (l != levels.back()) levels.push_back(l);
  }
  EXPECT_EQ(levels, (std::vector<std::string>{"L1", "L0", "L1"}));
  // Standing 0.46 m above the floor it is on: L0 before the lift, L1 (3.2 m) right after it.
  const BaseMotion& motion = sim.baseMotion();
  EXPECT_NEAR(motion.poseBefore(when).translation().z(), 0.46, 0.02);
  EXPECT_NEAR(motion.pose(when).translation().z(), 3.2 + 0.46, 0.02);
  EXPECT_NEAR(motion.pose(motion.duration()).translation().z(), 3.2 + 0.46, 1e-9);
  // The odometry does not see the lift: its height stays as it was through it.
  const auto odometry = sim.odometry(when + 1.0);
  ASSERT_GE(odometry.size(), 2u);
  EXPECT_LT(
      std::abs(odometry.back().pose.translation().z() - odometry.front().pose.translation().z()),
      0.3);
}

}  // namespace
}  // namespace isg::sim
