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

namespace isg::sim {
namespace {

// An open floor: a 20 m × 10 m façade of walls with a 3 m gap in its east side, two columns and
// no rooms at all (a site plan, a raster plan whose walls enclose nothing).
PlannedRoute openFloorTour(const nlohmann::json& robot, const nlohmann::json& more_walls = {},
                           const nlohmann::json& rooms = {}, const nlohmann::json& as_built = {}) {
  nlohmann::json document = {
      {"format", "isg.scenario"},
      {"version", 1},
      {"plan",
       {{"format", "isg.plan"},
        {"version", 1},
        {"levels",
         {{{"id", "L0"},
           {"height", 3.0},
           {"walls",
            {{{"id", "S"}, {"start", {0, 0}}, {"end", {20, 0}}, {"thickness", 0.3}},
             {{"id", "E1"}, {"start", {20, 0}}, {"end", {20, 3.5}}, {"thickness", 0.3}},
             {{"id", "E2"}, {"start", {20, 6.5}}, {"end", {20, 10}}, {"thickness", 0.3}},
             {{"id", "N"}, {"start", {20, 10}}, {"end", {0, 10}}, {"thickness", 0.3}},
             {{"id", "W"}, {"start", {0, 10}}, {"end", {0, 0}}, {"thickness", 0.3}},
             {{"id", "C1"}, {"start", {6.8, 5}}, {"end", {7.2, 5}}, {"thickness", 0.4}},
             {{"id", "C2"}, {"start", {12.8, 5}}, {"end", {13.2, 5}}, {"thickness", 0.4}}}}}}}}}};
  if (!robot.is_null()) document["robot"] = robot;
  for (const auto& wall : more_walls) document["plan"]["levels"][0]["walls"].push_back(wall);
  if (!rooms.empty()) document["plan"]["levels"][0]["rooms"] = rooms;
  if (!as_built.is_null()) document["as_built"] = as_built;
  const common::JsonSource source{"scenario.json", nullptr};
  const bim::Scenario scenario = bim::parseScenario(
      common::JsonNode(document, "", source),
      [](const common::JsonNode&) -> bim::LoadedPlan { throw std::logic_error("inline plan"); });
  const OccupancyGrid grid(scenario.plan, scenario.as_built, scenario.robot.level);
  std::mt19937_64 rng(1);
  return planRoute(scenario, grid, rng);
}

TEST(Tour, AnOpenFloorIsWalkedOverAFiveMetreLatticeFromItsMostOpenPoint) {
  const PlannedRoute route = openFloorTour(nullptr);
  ASSERT_GE(route.waypoints.size(), 2u);
  // The start: the façade's middle, (10, 5), lies between the columns, 2.6 m from either's
  // face and 4.85 m from the long walls' faces: open, so it is the start.
  EXPECT_NEAR(route.waypoints.front().x(), 10.0, 0.05);
  EXPECT_NEAR(route.waypoints.front().y(), 5.0, 0.05);
  // The lattice: 4 × 2 points 5 m apart in the 20.3 m × 10.3 m hull, every one reached.
  int open_floor_targets = 0;
  for (const auto& target : route.targets) {
    if (target.label.rfind("open floor ", 0) == 0) ++open_floor_targets;
  }
  EXPECT_EQ(open_floor_targets, 8);
  EXPECT_TRUE(route.visited_rooms.empty());
  EXPECT_TRUE(route.skipped_rooms.empty());
  // Every waypoint inside the façade, never through its gap to the outside.
  for (const auto& p : route.waypoints) {
    EXPECT_GT(p.x(), 0.15);
    EXPECT_LT(p.x(), 19.85);
    EXPECT_GT(p.y(), 0.15);
    EXPECT_LT(p.y(), 9.85);
  }
}

// A part of the site the plan does not show: a 5.85 m × 5 m bay built beyond the east gap
// (as_built.extra_walls). The tour walks into it, out of the drawn outline and back, and nowhere
// else outside the façade.
TEST(Tour, AnOpenFloorsTourWalksIntoWhatWasBuiltBeyondItsFacade) {
  const nlohmann::json annex = {
      {"extra_walls",
       {{{"start", {20.15, 2.5}}, {"end", {26, 2.5}}, {"thickness", 0.2}},
        {{"start", {26, 2.5}}, {"end", {26, 7.5}}, {"thickness", 0.2}},
        {{"start", {26, 7.5}}, {"end", {20.15, 7.5}}, {"thickness", 0.2}}}}};
  const PlannedRoute route = openFloorTour(nullptr, {}, {}, annex);
  double farthest = 0.0;
  for (const auto& p : route.waypoints) {
    farthest = std::max(farthest, p.x());
    if (p.x() > 20.15) {  // outside the façade: only in the bay built beyond it
      EXPECT_GT(p.y(), 2.6 + 0.3) << p.transpose();
      EXPECT_LT(p.y(), 7.4 - 0.3) << p.transpose();
      EXPECT_LT(p.x(), 25.9 - 0.3) << p.transpose();
    }
  }
  EXPECT_GT(farthest, 22.0);
  // The drawn floor is toured as well: its lattice points, now spread over the grown outline.
  int open_floor_targets = 0;
  for (const auto& target : route.targets) {
    if (target.label.rfind("open floor ", 0) == 0) ++open_floor_targets;
  }
  EXPECT_GE(open_floor_targets, 8);
}

TEST(Tour, AnOpenFloorWhoseMiddleIsAClosedShaftStartsOnTheFloorOutsideIt) {
  // A closed 3 m × 3 m shaft round the façade's middle (10, 5): started there, the robot would
  // see its four walls and nothing else. It starts in the largest stretch of floor instead and
  // tours it.
  const PlannedRoute route = openFloorTour(
      nullptr, {{{"id", "K1"}, {"start", {8.5, 3.5}}, {"end", {11.5, 3.5}}, {"thickness", 0.2}},
                {{"id", "K2"}, {"start", {11.5, 3.5}}, {"end", {11.5, 6.5}}, {"thickness", 0.2}},
                {{"id", "K3"}, {"start", {11.5, 6.5}}, {"end", {8.5, 6.5}}, {"thickness", 0.2}},
                {{"id", "K4"}, {"start", {8.5, 6.5}}, {"end", {8.5, 3.5}}, {"thickness", 0.2}}});
  const Eigen::Vector2d start = route.waypoints.front();
  EXPECT_FALSE(start.x() > 8.5 && start.x() < 11.5 && start.y() > 3.5 && start.y() < 6.5)
      << start.transpose();
  int open_floor_targets = 0;
  for (const auto& target : route.targets) {
    if (target.label.rfind("open floor ", 0) == 0) ++open_floor_targets;
  }
  // The 4 × 2 lattice, less the points inside the shaft that no path reaches.
  EXPECT_GE(open_floor_targets, 6);
  for (const auto& p : route.waypoints) {
    EXPECT_FALSE(p.x() > 8.5 && p.x() < 11.5 && p.y() > 3.5 && p.y() < 6.5) << p.transpose();
  }
}

TEST(Tour, AnOpenFloorWithAFewRoomsIsToured) {
  // A 3 m × 3 m room in the floor's south-west (9 m² of the 209 m² façade: under a quarter), its
  // doorway a 1.2 m gap in its north wall: the level is still an open floor. The robot starts on
  // the floor, not in the room, tours the lattice and then the room.
  const PlannedRoute route =
      openFloorTour(nullptr,
                    {{{"id", "K1"}, {"start", {1, 1}}, {"end", {4, 1}}, {"thickness", 0.2}},
                     {{"id", "K2"}, {"start", {4, 1}}, {"end", {4, 4}}, {"thickness", 0.2}},
                     {{"id", "K3"}, {"start", {4, 4}}, {"end", {3.2, 4}}, {"thickness", 0.2}},
                     {{"id", "K4"}, {"start", {2.0, 4}}, {"end", {1, 4}}, {"thickness", 0.2}},
                     {{"id", "K5"}, {"start", {1, 4}}, {"end", {1, 1}}, {"thickness", 0.2}}},
                    {{{"id", "K"}, {"outline", {{1.1, 1.1}, {3.9, 1.1}, {3.9, 3.9}, {1.1, 3.9}}}}});
  const Eigen::Vector2d start = route.waypoints.front();
  EXPECT_FALSE(start.x() > 1 && start.x() < 4 && start.y() > 1 && start.y() < 4);
  int open_floor_targets = 0;
  for (const auto& target : route.targets) {
    if (target.label.rfind("open floor ", 0) == 0) ++open_floor_targets;
  }
  EXPECT_GE(open_floor_targets, 7);
  EXPECT_EQ(route.visited_rooms, std::vector<std::string>{"K"});
  EXPECT_TRUE(route.skipped_rooms.empty());
}

TEST(Tour, AnOpenFloorStartsWhereTheScenarioSays) {
  const PlannedRoute route =
      openFloorTour({{"start", {{"pose", {2.0, 2.0, 0.5}}}}, {"route", "tour"}});
  EXPECT_DOUBLE_EQ(route.waypoints.front().x(), 2.0);
  EXPECT_DOUBLE_EQ(route.waypoints.front().y(), 2.0);
  EXPECT_DOUBLE_EQ(route.start_yaw, 0.5);
}

}  // namespace
}  // namespace isg::sim
