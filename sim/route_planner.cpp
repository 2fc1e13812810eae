#include "sim/route_planner.hpp"

#include "bim/facade.hpp"
#include "common/plural.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>

#include "bim/plan_geometry.hpp"
#include "bim/polygon.hpp"
#include "bim/stairs.hpp"
#include "sim/route_builder.hpp"

namespace isg::sim {

std::string formatPoint(const Eigen::Vector2d& p) {
  std::ostringstream out;
  out.precision(3);
  out << "(" << p.x() << ", " << p.y() << ")";
  return out.str();
}

std::string tooCloseReason(const Eigen::Vector2d& p, const std::string& what, double clearance) {
  char metres[32];
  std::snprintf(metres, sizeof metres, "%.2f", clearance);
  return "the robot cannot " + what + " at " + formatPoint(p) + ": it is less than " + metres +
         " m from a wall, clutter or the outside of the building";
}

namespace {

// "0.35 m", as messages give the clearance.
std::string formatMetres(double metres) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f m", metres);
  return text;
}

bool segmentIsClear(const OccupancyGrid& grid, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                    double clearance) {
  const double length = (b - a).norm();
  const int steps = std::max(1, int(std::ceil(length / (0.5 * grid.resolution()))));
  for (int i = 0; i <= steps; ++i) {
    if (grid.clearanceAt(a + (b - a) * (double(i) / steps)) < clearance) return false;
  }
  return true;
}

// Keeps only the points where the path must turn: from each kept point, the farthest later point
// that a straight, clear segment reaches.
std::vector<Eigen::Vector2d> straighten(const OccupancyGrid& grid,
                                        const std::vector<Eigen::Vector2d>& path,
                                        double clearance) {
  if (path.size() <= 2) return path;
  std::vector<Eigen::Vector2d> out{path.front()};
  std::size_t i = 0;
  while (i + 1 < path.size()) {
    std::size_t j = path.size() - 1;
    while (j > i + 1 && !segmentIsClear(grid, path[i], path[j], clearance)) --j;
    out.push_back(path[j]);
    i = j;
  }
  return out;
}

// The most open point of a room (ties: nearest its centroid); its centroid when that is open.
// The most open cell of those in [a, b] that `keep` keeps, nearest `centroid` among equals (the
// clearance in whole centimetres, so that a symmetric space picks the cell nearest its centre);
// `centroid` when none is kept.
template <typename Keep>
Eigen::Vector2d mostOpenCell(const OccupancyGrid& grid, const Eigen::Vector2i& a,
                             const Eigen::Vector2i& b, const Eigen::Vector2d& centroid, Keep keep) {
  double best_clearance = -1.0, best_distance = 0.0;
  Eigen::Vector2d best = centroid;
  for (int y = a.y(); y <= b.y(); ++y) {
    for (int x = a.x(); x <= b.x(); ++x) {
      if (!keep(x, y)) continue;
      const Eigen::Vector2d p = grid.centreOf({x, y});
      const double rounded = std::floor(grid.clearance({x, y}) * 100.0);
      const double d = (p - centroid).norm();
      if (rounded > best_clearance || (rounded == best_clearance && d < best_distance)) {
        best_clearance = rounded;
        best_distance = d;
        best = p;
      }
    }
  }
  return best;
}

Eigen::Vector2d roomCentre(const OccupancyGrid& grid, const bim::Room& room, bool prefer_centroid,
                           double clearance) {
  const Eigen::Vector2d centroid = bim::centroid(room.outline);
  if (prefer_centroid && bim::containsPoint(room.outline, centroid) &&
      grid.clearanceAt(centroid) >= clearance) {
    return centroid;
  }
  Eigen::Vector2d lo = room.outline[0], hi = room.outline[0];
  for (const auto& p : room.outline) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return mostOpenCell(grid, grid.cellOf(lo), grid.cellOf(hi), centroid, [&](int x, int y) {
    return bim::containsPoint(room.outline, grid.centreOf({x, y}));
  });
}

// Where the robot starts on an open floor: in the largest stretch of floor it can walk (cells
// with its clearance joined 8-connected, as paths go), so that a façade whose middle falls in a
// closed shaft or stairwell does not shut the tour in there; at the façade's centroid when that
// lies in it, else its most open cell there nearest the centroid. When the centroid's stretch is
// the largest this is roomCentre's choice.
Eigen::Vector2d openFloorStart(const OccupancyGrid& grid, const bim::Room& inside,
                               double clearance) {
  const int w = grid.width(), h = grid.height();
  std::vector<int> label(std::size_t(w) * std::size_t(h), -1);
  const auto walkable = [&](int x, int y) {
    return grid.clearance({x, y}) >= clearance &&
           bim::containsPoint(inside.outline, grid.centreOf({x, y}));
  };
  std::vector<int> sizes, queue;
  for (int y0 = 0; y0 < h; ++y0) {
    for (int x0 = 0; x0 < w; ++x0) {
      if (label[std::size_t(y0) * w + x0] >= 0 || !walkable(x0, y0)) continue;
      const int id = int(sizes.size());
      sizes.push_back(0);
      queue.assign(1, y0 * w + x0);
      label[std::size_t(y0) * w + x0] = id;
      while (!queue.empty()) {
        const int cell = queue.back();
        queue.pop_back();
        ++sizes[std::size_t(id)];
        const int cx = cell % w, cy = cell / w;
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            const int x = cx + dx, y = cy + dy;
            if (x < 0 || y < 0 || x >= w || y >= h) continue;
            int& l = label[std::size_t(y) * w + x];
            if (l >= 0 || !walkable(x, y)) continue;
            l = id;
            queue.push_back(y * w + x);
          }
        }
      }
    }
  }
  const Eigen::Vector2d centroid = bim::centroid(inside.outline);
  if (sizes.empty()) return roomCentre(grid, inside, true, clearance);
  const int largest = int(std::max_element(sizes.begin(), sizes.end()) - sizes.begin());
  const Eigen::Vector2i at = grid.cellOf(centroid);
  if (grid.inside(at) && label[std::size_t(at.y()) * w + at.x()] == largest) {
    return roomCentre(grid, inside, true, clearance);
  }
  return mostOpenCell(grid, {0, 0}, {w - 1, h - 1}, centroid,
                      [&](int x, int y) { return label[std::size_t(y) * w + x] == largest; });
}

}  // namespace

Eigen::Vector2d roomGoal(const OccupancyGrid& grid, const bim::Room& room, double clearance) {
  return roomCentre(grid, room, true, clearance);
}

std::vector<Eigen::Vector2d> straightPath(PathSearch& search, const Eigen::Vector2d& from,
                                          const Eigen::Vector2d& to, double clearance) {
  const auto path = search.find(from, to, clearance);
  if (path.empty()) return path;
  return straighten(search.grid(), path, clearance);
}

std::vector<Eigen::Vector2d> straightPath(const OccupancyGrid& grid, const Eigen::Vector2d& from,
                                          const Eigen::Vector2d& to, double clearance) {
  PathSearch search(grid);
  return straightPath(search, from, to, clearance);
}

std::vector<Eigen::Vector2d> findPath(const OccupancyGrid& grid, const Eigen::Vector2d& from,
                                      const Eigen::Vector2d& to, double min_clearance) {
  return PathSearch(grid).find(from, to, min_clearance);
}

namespace {

// Why a flight could not be climbed from where the route is.
std::string flightBlocked(const Flight& flight, const Eigen::Vector2d& from, double clearance) {
  return "flight \"" + flight.stair->id + "\" cannot be reached from " + formatPoint(from) +
         " or stepped off, keeping " + formatMetres(clearance) + " from walls and clutter";
}

// An open floor's tour (a level without rooms, docs/simulation.md "Open floors"): the points of a
// square lattice `kOpenFloorSpacing` apart inside the façade's outline (touredOutline), each moved
// to the most open cell within half a spacing, visited nearest first from where the robot is; a
// point no path reaches is left out.
constexpr double kOpenFloorSpacing = 5.0;  // m: a VLP-16 sees every wall of a 5 m cell around it

// The outline an open floor's tour covers: the plan's façade, grown to take in the unplanned
// walls built beyond it (a part of the site the plan does not show, reached through a gap): the
// walk leaves the drawn outline there for a while, as walks on sites do. Without such walls it
// is the plan's façade, bit for bit.
bim::Polygon2 touredOutline(const bim::Level& level, const bim::AsBuilt& as_built) {
  std::vector<const bim::ExtraWall*> here;
  for (const auto& extra : as_built.extra_walls) {
    if (extra.level == level.id) here.push_back(&extra);
  }
  if (here.empty()) return bim::facadeOutline(level);
  bim::Level grown = level;
  for (const bim::ExtraWall* extra : here) {
    bim::Wall wall;
    wall.id = extra->id;
    wall.start = extra->start;
    wall.end = extra->end;
    wall.thickness = extra->thickness;
    wall.height = extra->height.value_or(level.height);
    wall.base = extra->base;
    grown.walls.push_back(wall);
  }
  return bim::facadeOutline(grown);
}

void tourOpenFloor(RouteBuilder& builder, const bim::AsBuilt& as_built) {
  const bim::Level& level = builder.level();
  const OccupancyGrid& grid = builder.grid();
  const bim::Polygon2 outline = touredOutline(level, as_built);
  if (outline.empty()) return;
  Eigen::Vector2d lo = outline[0], hi = outline[0];
  for (const auto& p : outline) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double clearance = builder.clearance();
  const int reach = std::max(1, int(0.5 * kOpenFloorSpacing / grid.resolution()));
  std::vector<Eigen::Vector2d> points;
  const Eigen::Vector2d extent = hi - lo;
  const int nx = std::max(1, int(extent.x() / kOpenFloorSpacing)),
            ny = std::max(1, int(extent.y() / kOpenFloorSpacing));
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      // Lattice points centred in the outline's box.
      const Eigen::Vector2d p =
          lo + Eigen::Vector2d((i + 0.5) * extent.x() / nx, (j + 0.5) * extent.y() / ny);
      if (!bim::containsPoint(outline, p)) continue;
      const Eigen::Vector2i c = grid.cellOf(p);
      double best = -1.0, best_distance = 0.0;
      Eigen::Vector2d at = p;
      for (int dy = -reach; dy <= reach; ++dy) {
        for (int dx = -reach; dx <= reach; ++dx) {
          const Eigen::Vector2i q(c.x() + dx, c.y() + dy);
          const double open = std::floor(grid.clearance(q) * 100.0);  // whole centimetres
          const double distance = double(dx * dx + dy * dy);
          if (open > best || (open == best && distance < best_distance)) {
            best = open, best_distance = distance, at = grid.centreOf(q);
          }
        }
      }
      if (best * 0.01 >= clearance) points.push_back(at);
    }
  }
  std::vector<char> done(points.size(), 0);
  for (std::size_t visited = 0; visited < points.size(); ++visited) {
    const Eigen::Vector2d here = builder.lastWaypoint();
    std::size_t next = points.size();
    for (std::size_t k = 0; k < points.size(); ++k) {
      if (!done[k] && (next == points.size() ||
                       (points[k] - here).squaredNorm() < (points[next] - here).squaredNorm())) {
        next = k;
      }
    }
    done[next] = 1;
    if (builder.goTo(points[next])) {
      builder.route().targets.push_back({"", "open floor " + std::to_string(next),
                                         int(builder.route().waypoints.size()) - 1, points[next],
                                         level.id});
    }
  }
}

// Tour of one level from where the route is: depth-first over the rooms joined by open doors,
// neighbours in id order, then the rooms joined without a door.
void tourLevel(RouteBuilder& builder, const bim::Scenario& scenario, std::set<std::string>& seen,
               const std::string& entry_room) {
  const bim::Level& level = builder.level();
  if (bim::isOpenFloor(level)) {
    tourOpenFloor(builder, scenario.as_built);
    // Then its few rooms (a core's toilets and stairs), through their doors or the free space.
    if (level.rooms.empty()) return;
  }
  std::map<std::string, std::set<std::string>> neighbours;
  for (const auto& door : level.doors) {
    if (door.rooms[0] == bim::kOutside || door.rooms[1] == bim::kOutside) continue;
    if (std::find(scenario.as_built.closed_doors.begin(), scenario.as_built.closed_doors.end(),
                  door.id) != scenario.as_built.closed_doors.end()) {
      continue;
    }
    neighbours[door.rooms[0]].insert(door.rooms[1]);
    neighbours[door.rooms[1]].insert(door.rooms[0]);
  }
  const double clearance = builder.clearance();
  std::vector<std::string> stack;
  auto visitFrom = [&](const std::string& from) {
    for (auto it = neighbours[from].rbegin(); it != neighbours[from].rend(); ++it) {
      if (!seen.count(*it)) stack.push_back(*it);
    }
    while (!stack.empty()) {
      const std::string room = stack.back();
      stack.pop_back();
      if (seen.count(room)) continue;
      if (!builder.goTo(roomCentre(builder.grid(), *level.findRoom(room), true, clearance))) {
        continue;
      }
      seen.insert(room);
      builder.reached(room);
      for (auto it = neighbours[room].rbegin(); it != neighbours[room].rend(); ++it) {
        if (!seen.count(*it)) stack.push_back(*it);
      }
    }
  };
  visitFrom(entry_room);
  // Rooms joined without a door (open-plan spaces, where no wall stands between two rooms) are
  // reached through the free space itself: each room left, in id order, that a path reaches from
  // where the robot is is visited, and the tour goes on through its doors.
  for (bool progress = true; progress;) {
    progress = false;
    for (const auto& room : level.rooms) {
      if (seen.count(room.id)) continue;
      if (!builder.goTo(roomCentre(builder.grid(), room, true, clearance))) continue;
      seen.insert(room.id);
      builder.reached(room.id);
      visitFrom(room.id);
      progress = true;
    }
  }
}

// The tour goes on to every level a flight of stairs leads to, depth first in plan order: it
// climbs to the next level not toured yet, tours it (and what it leads to), and comes back down
// the same flight when the level it left still has flights to levels not toured.
void tourLevelsFrom(RouteBuilder& builder, const bim::Scenario& scenario,
                    std::set<std::string>& seen_rooms, std::set<std::string>& toured_levels) {
  const bim::Level& here = builder.level();
  for (const Flight& flight : builder.flightsOf(here)) {
    const bim::Level& next = flight.otherThan(here);
    if (toured_levels.count(next.id)) continue;
    auto& why = builder.route().why_levels_skipped;
    if (&builder.level() != &here) {  // could not come back: stay where the tour is
      why.emplace(next.id, "flight \"" + flight.stair->id + "\" leads there from level \"" +
                               here.id + "\", to which the tour could not come back");
      continue;
    }
    if (!builder.climb(flight)) {
      why.emplace(next.id, flightBlocked(flight, builder.lastWaypoint(), builder.clearance()));
      continue;
    }
    toured_levels.insert(next.id);
    const std::string arrival = bim::roomAt(next, builder.lastWaypoint()).value_or("");
    if (!arrival.empty() && !seen_rooms.count(arrival)) {
      seen_rooms.insert(arrival);
      builder.reached(arrival);
    }
    tourLevel(builder, scenario, seen_rooms, arrival);
    tourLevelsFrom(builder, scenario, seen_rooms, toured_levels);
    // Back down (or up) only if this level has more to tour beyond other flights.
    const std::vector<Flight> flights = builder.flightsOf(here);
    const bool more = std::any_of(flights.begin(), flights.end(), [&](const Flight& f) {
      return !toured_levels.count(f.otherThan(here).id);
    });
    if (more && &builder.level() == &next) builder.climb(flight);
  }
}

}  // namespace

std::string unreachedPart(const PlannedRoute& route) {
  const bool rooms = !route.skipped_rooms.empty();
  const auto& ids = rooms ? route.skipped_rooms : route.skipped_levels;
  if (ids.empty()) return "";
  return std::string(rooms ? "room" : "level") + (ids.size() > 1 ? "s " : " ") +
         common::namedList(ids);
}

std::string coarseCellsNote(const PlannedRoute& route) {
  if (route.skipped_rooms.empty() || route.coarse_cells.empty()) return "";
  std::vector<std::string> levels;
  for (const auto& [level, cell] : route.coarse_cells) {
    char size[32];
    std::snprintf(size, sizeof size, "%.1f cm", 100.0 * cell);
    levels.push_back("\"" + level + "\" (" + size + ")");
  }
  return " (the route grid of level" + std::string(levels.size() > 1 ? "s " : " ") +
         common::namedList(levels) +
         " has coarser cells than asked, the level being too large for " +
         std::to_string(int(OccupancyGrid::kMaxCells / 1e6)) +
         " M of them: a doorway much under 1 m wide can be shut at that size)";
}

namespace {

// Where the walk starts: the given pose, the most open point of an open floor, or the start
// room's centre; `start_room` is the room it stands in ("" outside any).
Eigen::Vector2d routeStart(const bim::Scenario& scenario, const OccupancyGrid& grid,
                           std::mt19937_64& rng, PlannedRoute& route, std::string& start_room) {
  const bim::Level& level = *scenario.plan.findLevel(scenario.robot.level);
  const double clearance = scenario.robot.clearance;
  Eigen::Vector2d start;
  if (scenario.robot.start_pose) {
    start = scenario.robot.start_pose->head<2>();
    route.start_yaw = scenario.robot.start_pose->z();
    start_room = bim::roomAt(level, start).value_or("");
  } else if (!scenario.robot.start_room) {
    // An open floor: the most open point of the largest stretch of its inside, nearest the middle
    // of its façade.
    bim::Room inside;
    inside.outline = bim::facadeOutline(level);
    if (inside.outline.empty()) {
      throw common::InputError(
          scenario.source, "/robot/start",
          "level \"" + level.id + "\" has neither rooms nor walls to stand in");
    }
    start = openFloorStart(grid, inside, clearance);
    route.start_yaw =
        std::uniform_real_distribution<double>(-std::numbers::pi, std::numbers::pi)(rng);
  } else {
    start_room = *scenario.robot.start_room;
    start = roomCentre(grid, *level.findRoom(start_room), true, clearance);
    route.start_yaw =
        std::uniform_real_distribution<double>(-std::numbers::pi, std::numbers::pi)(rng);
  }
  return start;
}

// The route through the given waypoints, in order.
void throughWaypoints(const bim::Scenario& scenario, RouteBuilder& builder, PlannedRoute& route) {
  const bim::Route& plan = scenario.robot.route;
  const double clearance = scenario.robot.clearance;
  for (std::size_t i = 0; i < plan.waypoints.size(); ++i) {
    if (!builder.goTo(plan.waypoints[i])) {
      throw common::InputError(scenario.source, "/robot/route/waypoints/" + std::to_string(i),
                               "no path from " + formatPoint(route.waypoints.back()) + " to " +
                                   formatPoint(plan.waypoints[i]) + " keeps " +
                                   formatMetres(clearance) + " from walls and clutter");
    }
    route.targets.push_back({"", "waypoint " + std::to_string(i), int(route.waypoints.size()) - 1,
                             plan.waypoints[i], scenario.robot.level});
  }
}

// The route through the given rooms, in order, up and down the flights to rooms on other levels.
void throughRooms(const bim::Scenario& scenario, RouteBuilder& builder, PlannedRoute& route) {
  const bim::Route& plan = scenario.robot.route;
  const std::string& file = scenario.source;
  const double clearance = scenario.robot.clearance;
  for (std::size_t i = 0; i < plan.rooms.size(); ++i) {
    const bim::Level& room_level = *scenario.plan.levelOfRoom(plan.rooms[i]);
    const std::string pointer = "/robot/route/rooms/" + std::to_string(i);
    if (&room_level != &builder.level()) {
      const auto flights = builder.flightsTo(room_level);
      if (flights.empty()) {
        throw common::InputError(file, pointer,
                                 "room \"" + plan.rooms[i] + "\" is on level \"" + room_level.id +
                                     "\", which no flight of stairs leads to from level \"" +
                                     builder.level().id + "\"");
      }
      for (const Flight& flight : flights) {
        if (!builder.climb(flight)) {
          throw common::InputError(file, pointer,
                                   "room \"" + plan.rooms[i] + "\" on level \"" + room_level.id +
                                       "\" cannot be reached: " +
                                       flightBlocked(flight, route.waypoints.back(), clearance));
        }
      }
    }
    if (!builder.goTo(
            roomCentre(builder.grid(), *room_level.findRoom(plan.rooms[i]), true, clearance))) {
      throw common::InputError(file, pointer,
                               "room \"" + plan.rooms[i] + "\" cannot be reached from " +
                                   formatPoint(route.waypoints.back()) +
                                   " through open doors, keeping " + formatMetres(clearance) +
                                   " from walls and clutter");
    }
    builder.reached(plan.rooms[i]);
  }
}

// The tour: every room reachable on the start's level, then the levels the stairs lead to; what
// it could not reach is listed with why.
void tour(const bim::Scenario& scenario, RouteBuilder& builder, const std::string& start_room,
          PlannedRoute& route) {
  const bim::Level& level = *scenario.plan.findLevel(scenario.robot.level);
  std::set<std::string> seen{start_room};
  tourLevel(builder, scenario, seen, start_room);
  std::set<std::string> toured_levels{level.id};
  tourLevelsFrom(builder, scenario, seen, toured_levels);
  for (const auto& l : scenario.plan.levels) {
    if (!toured_levels.count(l.id)) {
      if (&l == &level) continue;
      route.skipped_levels.push_back(l.id);
      route.why_levels_skipped.emplace(l.id,
                                       "no flight of stairs leads to it from the levels toured");
      continue;
    }
    for (const auto& room : l.rooms) {
      if (!seen.count(room.id)) route.skipped_rooms.push_back(room.id);
    }
  }
}

}  // namespace

PlannedRoute planRoute(const bim::Scenario& scenario, const OccupancyGrid& grid,
                       std::mt19937_64& rng) {
  const bim::Level& level = *scenario.plan.findLevel(scenario.robot.level);
  const double clearance = scenario.robot.clearance;
  PlannedRoute route;
  RouteBuilder builder(scenario, grid, route);
  std::string start_room;
  const Eigen::Vector2d start = routeStart(scenario, grid, rng, route, start_room);
  const double start_clearance = grid.clearanceAt(start);
  if (start_clearance < clearance) {
    throw common::InputError(scenario.source, "/robot/start",
                             tooCloseReason(start, "stand", clearance));
  }
  builder.start(start);
  if (!start_room.empty()) {
    route.visited_rooms.push_back(start_room);
    route.targets.push_back({start_room, start_room, 0, start, level.id});
  }
  switch (scenario.robot.route.kind) {
    case bim::Route::Kind::kWaypoints:
      throughWaypoints(scenario, builder, route);
      break;
    case bim::Route::Kind::kRooms:
      throughRooms(scenario, builder, route);
      break;
    default:
      tour(scenario, builder, start_room, route);
  }
  return route;
}

}  // namespace isg::sim
