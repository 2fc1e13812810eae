#include "sim/route_builder.hpp"

#include <queue>

namespace isg::sim {

RouteBuilder::RouteBuilder(const bim::Scenario& scenario, const OccupancyGrid& robot_grid,
                           PlannedRoute& route)
    : scenario_(scenario), route_(&route), clearance_(scenario.robot.clearance) {
  level_ = scenario.plan.findLevel(scenario.robot.level);
  grids_.emplace(level_->id, &robot_grid);
  noteCoarseCells(level_->id, robot_grid);
}

void RouteBuilder::noteCoarseCells(const std::string& level, const OccupancyGrid& grid) {
  if (grid.resolution() > grid.askedResolution()) route_->coarse_cells[level] = grid.resolution();
}

void RouteBuilder::restart(PlannedRoute& route, const bim::Level& level) {
  route_ = &route;
  level_ = &level;
}

const OccupancyGrid& RouteBuilder::gridOf(const bim::Level& level) {
  auto found = grids_.find(level.id);
  if (found != grids_.end()) return *found->second;
  owned_.push_back(std::make_unique<OccupancyGrid>(scenario_.plan, scenario_.as_built, level.id));
  noteCoarseCells(level.id, *owned_.back());
  return *grids_.emplace(level.id, owned_.back().get()).first->second;
}

PathSearch& RouteBuilder::search() {
  auto& search = searches_[level_->id];
  if (!search) search = std::make_unique<PathSearch>(grid());
  return *search;
}

bool RouteBuilder::goTo(const Eigen::Vector2d& target) {
  const auto straight = straightPath(search(), route_->waypoints.back(), target, clearance_);
  if (straight.empty()) return false;
  for (auto it = straight.begin() + 1; it != straight.end(); ++it) push(*it);
  return true;
}

void RouteBuilder::reached(const std::string& room) {
  route_->visited_rooms.push_back(room);
  route_->targets.push_back(
      {room, room, int(route_->waypoints.size()) - 1, route_->waypoints.back(), level_->id});
}

std::vector<Flight> RouteBuilder::flightsOf(const bim::Level& level) const {
  std::vector<Flight> out;
  for (const auto& from : scenario_.plan.levels) {
    for (const auto& stair : from.stairs) {
      const bim::Level* to = scenario_.plan.findLevel(stair.to);
      if (&from != &level && to != &level) continue;
      out.push_back({&stair, &from, to, bim::computeStairGeometry(stair, from, *to)});
    }
  }
  return out;
}

bool RouteBuilder::climb(const Flight& flight) {
  const bim::Level& other = flight.otherThan(*level_);
  const auto here = flightEnd(flight, *level_);
  const auto there = flightEnd(flight, other);
  if (!here || !there) return false;
  const auto path = straightPath(search(), route_->waypoints.back(), here->approach, clearance_);
  if (path.empty()) return false;
  for (auto it = path.begin() + 1; it != path.end(); ++it) push(*it);
  push(here->edge);
  level_ = &other;
  push(there->edge);
  push(there->approach);
  return true;
}

std::vector<Flight> RouteBuilder::flightsTo(const bim::Level& target) const {
  std::map<const bim::Level*, std::vector<Flight>> path{{level_, {}}};
  std::queue<const bim::Level*> queue;
  queue.push(level_);
  while (!queue.empty()) {
    const bim::Level* at = queue.front();
    queue.pop();
    if (at == &target) return path[at];
    for (const Flight& f : flightsOf(*at)) {
      const bim::Level* next = &f.otherThan(*at);
      if (path.count(next)) continue;
      path[next] = path[at];
      path[next].push_back(f);
      queue.push(next);
    }
  }
  return {};
}

std::optional<RouteBuilder::FlightEnd> RouteBuilder::flightEnd(const Flight& flight,
                                                               const bim::Level& level) {
  const bool at_start = &level == flight.from;
  const Eigen::Vector2d edge = at_start ? flight.stair->start : flight.stair->end;
  const Eigen::Vector2d outward = at_start ? -flight.geometry.axis : flight.geometry.axis;
  const OccupancyGrid& grid = gridOf(level);
  for (double d = clearance_ + 0.05; d <= clearance_ + 2.0; d += 0.05) {
    const Eigen::Vector2d approach = edge + d * outward;
    if (grid.clearanceAt(approach) >= clearance_) return FlightEnd{edge, approach};
  }
  return std::nullopt;
}

void RouteBuilder::push(const Eigen::Vector2d& p) {
  route_->waypoints.push_back(p);
  route_->waypoint_levels.push_back(level_->id);
}

std::vector<Eigen::Vector3d> onTheirFloors(const bim::Plan& plan,
                                           const std::vector<Eigen::Vector2d>& waypoints,
                                           const std::vector<std::string>& waypoint_levels) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(waypoints.size());
  for (std::size_t i = 0; i < waypoints.size(); ++i) {
    const double floor_z = plan.findLevel(waypoint_levels[i])->elevation;
    out.emplace_back(waypoints[i].x(), waypoints[i].y(), floor_z);
  }
  return out;
}

}  // namespace isg::sim
