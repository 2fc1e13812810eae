#pragma once

#include <Eigen/Core>
#include <random>
#include <string>
#include <vector>

#include "bim/input_error.hpp"
#include "bim/scenario.hpp"
#include "sim/occupancy_grid.hpp"

namespace isg::sim {

// The robot's centre keeps at least this far from walls, clutter and closed doors.
inline constexpr double kMinClearance = 0.35;

struct PlannedRoute {
  std::vector<Eigen::Vector2d> waypoints;  // polyline of the robot's centre; [0] is the start
  double start_yaw = 0.0;
  std::vector<std::string> visited_rooms;  // in the order the route reaches them
  std::vector<std::string> skipped_rooms;  // a tour's rooms that cannot be reached
};

// Plans the scenario's route on its robot level as built (docs/simulation.md):
// - "tour": a depth-first walk over the rooms joined by open doors, from the start room, reaching
//   each room's most open point; rooms that cannot be reached are skipped (and listed);
// - {"rooms": [...]}: those rooms in order; one that cannot be reached is an error;
// - {"waypoints": [...]}: through those points; one that cannot be reached is an error.
// Paths are A* on the occupancy grid, costed to stay away from walls, then straightened where the
// straight line keeps kMinClearance. The start heading (when the scenario gives a room) is drawn
// from `rng`. Errors are InputErrors naming the scenario file and the JSON pointer.
PlannedRoute planRoute(const bim::Scenario& scenario, const OccupancyGrid& grid,
                       std::mt19937_64& rng);

// The A* path between two points (cell centres, endpoints included), or empty when there is none.
std::vector<Eigen::Vector2d> findPath(const OccupancyGrid& grid, const Eigen::Vector2d& from,
                                      const Eigen::Vector2d& to);

}  // namespace isg::sim
