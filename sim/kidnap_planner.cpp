#include "sim/kidnap_planner.hpp"

#include <cstdio>
#include <numbers>

#include "sim/route_builder.hpp"

namespace isg::sim {

void planKidnaps(const bim::Scenario& scenario, const OccupancyGrid& grid, PlannedRoute& route,
                 BaseMotion& trajectory, std::mt19937_64& rng) {
  if (scenario.robot.kidnap.empty()) return;
  const std::string& file = scenario.source;
  // One builder for every leg, so that each level's grid is made once.
  PlannedRoute unused;
  RouteBuilder builder(scenario, grid, unused);
  for (std::size_t i = 0; i < scenario.robot.kidnap.size(); ++i) {
    const bim::Kidnap& kidnap = scenario.robot.kidnap[i];
    const std::string pointer = "/robot/kidnap/" + std::to_string(i);
    if (kidnap.time >= trajectory.duration()) {
      char reason[128];
      std::snprintf(reason, sizeof reason,
                    "the robot's route ends at %.2f s, before the kidnap at %.2f s",
                    trajectory.duration(), kidnap.time);
      throw common::InputError(file, pointer + "/time", reason);
    }
    // What the current leg had not reached by then.
    const int leg = trajectory.legs() - 1;
    const std::vector<RouteTarget>& targets =
        leg == 0 ? route.targets : route.kidnaps.back().targets;
    std::vector<RouteTarget> remaining;
    for (const auto& target : targets) {
      if (trajectory.arrival(leg, target.waypoint) > kidnap.time) remaining.push_back(target);
    }
    const bim::Level& level =
        *scenario.plan.findLevel(kidnap.level.empty() ? scenario.robot.level : kidnap.level);
    const OccupancyGrid& level_grid = builder.gridOf(level);
    KidnapLeg next;
    next.time = kidnap.time;
    Eigen::Vector2d at;
    if (kidnap.room) {
      at = roomGoal(level_grid, *level.findRoom(*kidnap.room), scenario.robot.clearance);
      next.start_yaw =
          std::uniform_real_distribution<double>(-std::numbers::pi, std::numbers::pi)(rng);
    } else {
      at = kidnap.pose->head<2>();
      next.start_yaw = kidnap.pose->z();
    }
    if (level_grid.clearanceAt(at) < scenario.robot.clearance) {
      throw common::InputError(file, pointer + "/to",
                               tooCloseReason(at, "be put down", scenario.robot.clearance));
    }
    PlannedRoute walked;
    builder.restart(walked, level);
    builder.start(at);
    if (kidnap.room) walked.targets.push_back({*kidnap.room, *kidnap.room, 0, at, level.id});
    for (const auto& target : remaining) {
      if (kidnap.room && target.room == *kidnap.room) continue;  // put down in it
      // On another level: by the flights that lead there, as the route planner goes.
      const bim::Level& target_level = *scenario.plan.findLevel(target.level);
      bool reachable = true;
      if (&target_level != &builder.level()) {
        const std::vector<Flight> flights = builder.flightsTo(target_level);
        reachable = !flights.empty();
        for (const Flight& flight : flights) {
          if (!(reachable = builder.climb(flight))) break;
        }
      }
      if (!reachable || !builder.goTo(target.goal)) {
        route.skipped_rooms.push_back(target.label);
        continue;
      }
      walked.targets.push_back({target.room, target.label, int(walked.waypoints.size()) - 1,
                                target.goal, target_level.id});
    }
    next.waypoints = std::move(walked.waypoints);
    next.waypoint_levels = std::move(walked.waypoint_levels);
    next.targets = std::move(walked.targets);
    trajectory.appendLeg(next.time,
                         onTheirFloors(scenario.plan, next.waypoints, next.waypoint_levels),
                         next.start_yaw);
    route.kidnaps.push_back(std::move(next));
  }
  if (route.kidnaps.empty()) return;
  // The rooms the robot reached: each leg's up to the next kidnap.
  route.visited_rooms.clear();
  for (int leg = 0; leg < trajectory.legs(); ++leg) {
    const auto& targets = leg == 0 ? route.targets : route.kidnaps[leg - 1].targets;
    const double until =
        leg + 1 < trajectory.legs() ? route.kidnaps[leg].time : trajectory.duration() + 1.0;
    for (const auto& target : targets) {
      if (!target.room.empty() && trajectory.arrival(leg, target.waypoint) <= until) {
        route.visited_rooms.push_back(target.room);
      }
    }
  }
}

}  // namespace isg::sim
