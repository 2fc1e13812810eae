// The tour over rooms an imported building has: residential doors narrower than the default
// clearance allows (robot.clearance), and open-plan rooms with no wall and no door between them.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "bim/scenario.hpp"
#include "common/json_reader.hpp"
#include "sim/occupancy_grid.hpp"
#include "sim/route_planner.hpp"

namespace isg::sim {
namespace {

// A 6 m × 4 m box split at x = 3 by a 0.1 m wall with a 0.78 m door (clear width of a 2'8"
// residential door), and its east half two open-plan rooms (north, south) with no wall between.
nlohmann::json scenarioJson(double door_width, std::optional<double> clearance) {
  nlohmann::json robot = {{"start", {{"room", "W"}}}, {"route", "tour"}};
  if (clearance) robot["clearance"] = *clearance;
  return {{"format", "isg.scenario"},
          {"version", 1},
          {"seed", 3u},
          {"robot", robot},
          {"plan",
           {{"format", "isg.plan"},
            {"version", 1},
            {"levels",
             {{{"id", "L0"},
               {"height", 3.0},
               {"walls",
                {{{"id", "A"}, {"start", {0, 0}}, {"end", {6, 0}}, {"thickness", 0.2}},
                 {{"id", "B"}, {"start", {6, 0}}, {"end", {6, 4}}, {"thickness", 0.2}},
                 {{"id", "C"}, {"start", {6, 4}}, {"end", {0, 4}}, {"thickness", 0.2}},
                 {{"id", "D"}, {"start", {0, 4}}, {"end", {0, 0}}, {"thickness", 0.2}},
                 {{"id", "M"}, {"start", {3, 0}}, {"end", {3, 4}}, {"thickness", 0.1}}}},
               {"doors",
                {{{"id", "DM"},
                  {"wall", "M"},
                  {"offset", 1.0},
                  {"width", door_width},
                  {"height", 2.0}}}},
               {"rooms",
                {{{"id", "W"}, {"outline", {{0.1, 0.1}, {2.95, 0.1}, {2.95, 3.9}, {0.1, 3.9}}}},
                 {{"id", "ES"}, {"outline", {{3.05, 0.1}, {5.9, 0.1}, {5.9, 2.0}, {3.05, 2.0}}}},
                 {{"id", "EN"},
                  {"outline", {{3.05, 2.0}, {5.9, 2.0}, {5.9, 3.9}, {3.05, 3.9}}}}}}}}}}}};
}

PlannedRoute tour(double door_width, std::optional<double> clearance) {
  const nlohmann::json document = scenarioJson(door_width, clearance);
  const common::JsonSource source{"scenario.json", nullptr};
  const bim::Scenario scenario = bim::parseScenario(
      common::JsonNode(document, "", source),
      [](const common::JsonNode&) -> bim::LoadedPlan { throw std::logic_error("inline plan"); });
  const OccupancyGrid grid(scenario.plan, scenario.as_built, scenario.robot.level);
  std::mt19937_64 rng(1);
  return planRoute(scenario, grid, rng);
}

TEST(Tour, ANarrowDoorNeedsALowerClearance) {
  // 0.78 m: half of it less a cell's diagonal (0.07 m) is 0.32 m, under the default 0.35 m.
  const PlannedRoute narrow = tour(0.78, std::nullopt);
  EXPECT_EQ(narrow.visited_rooms, std::vector<std::string>{"W"});
  EXPECT_EQ(narrow.skipped_rooms, (std::vector<std::string>{"ES", "EN"}));
  // With 0.3 m it passes, and the open-plan room beyond is reached without a door.
  const PlannedRoute passes = tour(0.78, 0.3);
  EXPECT_EQ(passes.visited_rooms, (std::vector<std::string>{"W", "ES", "EN"}));
  EXPECT_TRUE(passes.skipped_rooms.empty());
}

TEST(Tour, OpenPlanRoomsAreReachedThroughTheFreeSpace) {
  // ES is joined to W by the door, EN to ES by no door at all.
  const PlannedRoute route = tour(0.9, std::nullopt);
  EXPECT_EQ(route.visited_rooms, (std::vector<std::string>{"W", "ES", "EN"}));
  EXPECT_TRUE(route.skipped_rooms.empty());
}

}  // namespace
}  // namespace isg::sim
