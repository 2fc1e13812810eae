#pragma once

#include <Eigen/Core>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bim/scenario.hpp"
#include "bim/stairs.hpp"
#include "sim/occupancy_grid.hpp"
#include "sim/route_planner.hpp"

namespace isg::sim {

// A flight of stairs with the two levels it joins.
struct Flight {
  const bim::Stair* stair;
  const bim::Level* from;  // the level that declares it (its `start` edge)
  const bim::Level* to;
  bim::StairGeometry geometry;

  const bim::Level& otherThan(const bim::Level& level) const {
    return &level == from ? *to : *from;
  }
};

// Builds a route over the levels of a building into a PlannedRoute's waypoints: per level, paths
// on that level's occupancy grid (made when first needed, kept for the builder's life); between
// levels, the flights of stairs walked straight from an approach point before one edge to one
// beyond the other. The route planner builds the first leg with it, the kidnap planner the legs
// after each kidnap.
class RouteBuilder {
 public:
  // Starts on the scenario's robot level, whose grid is `robot_grid`, writing into `route`.
  RouteBuilder(const bim::Scenario& scenario, const OccupancyGrid& robot_grid, PlannedRoute& route);

  // Writes from now on into `route`, standing on `level` (a kidnap's new leg).
  void restart(PlannedRoute& route, const bim::Level& level);

  const bim::Level& level() const { return *level_; }
  const OccupancyGrid& grid() { return gridOf(*level_); }
  const OccupancyGrid& gridOf(const bim::Level& level);
  // The path search on the current level's grid, kept for the builder's life like the grid.
  PathSearch& search();
  double clearance() const { return clearance_; }
  PlannedRoute& route() { return *route_; }

  void start(const Eigen::Vector2d& at) { push(at); }
  const Eigen::Vector2d& lastWaypoint() const { return route_->waypoints.back(); }

  // A clear path on the current level to `target`; false (and nothing added) when there is none.
  bool goTo(const Eigen::Vector2d& target);

  // The route has reached `room` at its last waypoint.
  void reached(const std::string& room);

  // The flights that start or end on `level`, in plan order.
  std::vector<Flight> flightsOf(const bim::Level& level) const;

  // Walks `flight` from the current level to its other one: to the approach point on this level,
  // onto the edge, up or down the steps to the other edge, and on to the approach point there.
  // False (and nothing added) when the approach on this level cannot be reached or there is no
  // clear place to step off on the other.
  bool climb(const Flight& flight);

  // The flights that lead from the current level to `target`, fewest first (breadth first,
  // flights in plan order); empty when none does (or when `target` is the current level).
  std::vector<Flight> flightsTo(const bim::Level& target) const;

 private:
  struct FlightEnd {
    Eigen::Vector2d edge, approach;
  };
  // Where a flight meets `level`: its edge there and the nearest point straight out from it where
  // the robot stands clear of everything (the stairwell included), within 2 m; nullopt if none.
  std::optional<FlightEnd> flightEnd(const Flight& flight, const bim::Level& level);

  void push(const Eigen::Vector2d& p);
  // Writes the level's cell size into the route's coarse_cells when coarser than asked for.
  void noteCoarseCells(const std::string& level, const OccupancyGrid& grid);

  const bim::Scenario& scenario_;
  PlannedRoute* route_;
  double clearance_;
  const bim::Level* level_;
  std::map<std::string, const OccupancyGrid*> grids_;
  std::vector<std::unique_ptr<OccupancyGrid>> owned_;
  std::map<std::string, std::unique_ptr<PathSearch>> searches_;  // by level id, made when needed
};

// The route's waypoints in 3D: each at the elevation of its level (waypoint_levels[i]).
std::vector<Eigen::Vector3d> onTheirFloors(const bim::Plan& plan,
                                           const std::vector<Eigen::Vector2d>& waypoints,
                                           const std::vector<std::string>& waypoint_levels);

}  // namespace isg::sim
