#include "sim/kidnap_planner.hpp"

#include <cstdio>
#include <numbers>

namespace isg::sim {

void planKidnaps(const bim::Scenario& scenario, const OccupancyGrid& grid, PlannedRoute& route,
                 BaseMotion& trajectory, std::mt19937_64& rng) {
  if (scenario.robot.kidnap.empty()) return;
  const bim::Level& level = *scenario.plan.findLevel(scenario.robot.level);
  const std::string& file = scenario.source;
  for (std::size_t i = 0; i < scenario.robot.kidnap.size(); ++i) {
    const bim::Kidnap& kidnap = scenario.robot.kidnap[i];
    const std::string pointer = "/robot/kidnap/" + std::to_string(i);
    if (kidnap.time >= trajectory.duration()) {
      char reason[128];
      std::snprintf(reason, sizeof reason,
                    "the robot's route ends at %.2f s, before the kidnap at %.2f s",
                    trajectory.duration(), kidnap.time);
      throw bim::InputError(file, pointer + "/time", reason);
    }
    // What the current leg had not reached by then.
    const int leg = trajectory.legs() - 1;
    const std::vector<RouteTarget>& targets =
        leg == 0 ? route.targets : route.kidnaps.back().targets;
    std::vector<RouteTarget> remaining;
    for (const auto& target : targets) {
      if (trajectory.arrival(leg, target.waypoint) > kidnap.time) remaining.push_back(target);
    }
    KidnapLeg next;
    next.time = kidnap.time;
    Eigen::Vector2d at;
    if (kidnap.room) {
      at = roomGoal(grid, *level.findRoom(*kidnap.room), scenario.robot.clearance);
      next.start_yaw =
          std::uniform_real_distribution<double>(-std::numbers::pi, std::numbers::pi)(rng);
    } else {
      at = kidnap.pose->head<2>();
      next.start_yaw = kidnap.pose->z();
    }
    if (grid.clearanceAt(at) < scenario.robot.clearance) {
      throw bim::InputError(file, pointer + "/to",
                            tooCloseReason(at, "be put down", scenario.robot.clearance));
    }
    next.waypoints.push_back(at);
    if (kidnap.room) next.targets.push_back({*kidnap.room, *kidnap.room, 0, at, level.id});
    for (const auto& target : remaining) {
      if (kidnap.room && target.room == *kidnap.room) continue;  // put down in it
      // A kidnap puts the robot down on its scenario's level: what the tour had left on other
      // levels is not walked to after it.
      if (target.level != level.id) {
        route.skipped_rooms.push_back(target.label);
        continue;
      }
      const auto path =
          straightPath(grid, next.waypoints.back(), target.goal, scenario.robot.clearance);
      if (path.empty()) {
        route.skipped_rooms.push_back(target.label);
        continue;
      }
      next.waypoints.insert(next.waypoints.end(), path.begin() + 1, path.end());
      next.targets.push_back(
          {target.room, target.label, int(next.waypoints.size()) - 1, target.goal, level.id});
    }
    trajectory.appendLeg(next.time, next.waypoints, next.start_yaw);
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
