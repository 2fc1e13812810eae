#pragma once

#include <Eigen/Core>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "bim/scenario.hpp"
#include "common/input_error.hpp"
#include "sim/occupancy_grid.hpp"
#include "sim/path_search.hpp"

namespace isg::sim {

// The robot's centre keeps at least this far from walls, clutter and closed doors, unless the
// scenario says otherwise (robot.clearance).
inline constexpr double kMinClearance = bim::kDefaultRobotClearance;

// A place the route goes to: a room (tour, rooms) or a waypoint of the scenario's list.
struct RouteTarget {
  std::string room;   // empty for a waypoint
  std::string label;  // the room's id, or "waypoint N"
  int waypoint = 0;   // index of the leg's waypoint at which it is reached
  Eigen::Vector2d goal = Eigen::Vector2d::Zero();  // where the robot goes for it
  std::string level;                               // the level `goal` is on
};

// After a kidnap (scenario robot.kidnap): put down at waypoints[0] at `time`, the robot goes on
// to the targets it had not reached yet, by stairs when they are on other levels.
struct KidnapLeg {
  double time = 0.0;
  std::vector<Eigen::Vector2d> waypoints;
  std::vector<std::string> waypoint_levels;  // as PlannedRoute's
  double start_yaw = 0.0;
  std::vector<RouteTarget> targets;
};

struct PlannedRoute {
  std::vector<Eigen::Vector2d> waypoints;  // polyline of the robot's centre; [0] is the start
  // The level each waypoint is on. Two consecutive waypoints on different levels are the two
  // edges of a flight of stairs, walked straight (bim/stairs.hpp).
  std::vector<std::string> waypoint_levels;
  double start_yaw = 0.0;
  std::vector<RouteTarget> targets;  // of `waypoints`, in order
  std::vector<KidnapLeg> kidnaps;
  std::vector<std::string> visited_rooms;   // in the order the route reaches them
  std::vector<std::string> skipped_rooms;   // rooms (and waypoints after a kidnap) not reachable
  std::vector<std::string> skipped_levels;  // levels no flight of stairs the tour took leads to
  // Why each of skipped_levels was (a flight that cannot be reached or stepped off, or none
  // leading there), by level id: what the warning says.
  std::map<std::string, std::string> why_levels_skipped;
  // The levels whose route grid has coarser cells than asked for (too large for
  // OccupancyGrid::kMaxCells of them): their cell size, by level id. Narrow doorways can be shut
  // at that size, which a message about rooms not reached says.
  std::map<std::string, double> coarse_cells;
};

// Plans the scenario's route from its robot level as built (docs/simulation.md):
// - "tour": a depth-first walk over the rooms joined by open doors, from the start room, reaching
//   each room's most open point; rooms that cannot be reached are skipped (and listed); then on
//   to every level the level's flights of stairs lead to, toured the same way, depth first;
// - {"rooms": [...]}: those rooms in order, on any level a chain of flights reaches; one that
//   cannot be reached is an error;
// - {"waypoints": [...]}: through those points; one that cannot be reached is an error.
// Paths are A* on the occupancy grid, costed to stay away from walls, then straightened where the
// straight line keeps kMinClearance. The start heading (when the scenario gives a room) is drawn
// from `rng`. Errors are InputErrors naming the scenario file and the JSON pointer.
// The clearance kept is the scenario's robot.clearance.
PlannedRoute planRoute(const bim::Scenario& scenario, const OccupancyGrid& grid,
                       std::mt19937_64& rng);

// What a tour could not reach, for the messages that refuse a generated building: "room R3",
// "rooms R3, R4", else "level L1", "levels L1, L2"; empty when it reached everything.
std::string unreachedPart(const PlannedRoute& route);
// When rooms were not reached and a level's route grid has coarser cells than asked for, the
// likely cause, to end that message: " (the route grid of level "L0" (6.1 cm) has coarser cells
// …)"; else empty.
std::string coarseCellsNote(const PlannedRoute& route);

// "(x, y)" with 3 significant digits, as error messages name points.
std::string formatPoint(const Eigen::Vector2d& p);

// The error's reason when the robot cannot `what` ("stand", "be put down") at p: closer than
// kMinClearance to something.
std::string tooCloseReason(const Eigen::Vector2d& p, const std::string& what,
                           double clearance = kMinClearance);

// Where the route goes in a room: its centroid when open enough, else its most open point.
Eigen::Vector2d roomGoal(const OccupancyGrid& grid, const bim::Room& room,
                         double clearance = kMinClearance);

// The A* path from `from` to `to`, straightened where a straight line keeps kMinClearance; empty
// when there is none. With a PathSearch, on its grid and reusing its state (many searches on one
// grid: a tour); with a grid, one search.
std::vector<Eigen::Vector2d> straightPath(PathSearch& search, const Eigen::Vector2d& from,
                                          const Eigen::Vector2d& to,
                                          double clearance = kMinClearance);
std::vector<Eigen::Vector2d> straightPath(const OccupancyGrid& grid, const Eigen::Vector2d& from,
                                          const Eigen::Vector2d& to,
                                          double clearance = kMinClearance);

// The A* path between two points (cell centres, endpoints included), or empty when there is none.
std::vector<Eigen::Vector2d> findPath(const OccupancyGrid& grid, const Eigen::Vector2d& from,
                                      const Eigen::Vector2d& to, double clearance = kMinClearance);

}  // namespace isg::sim
