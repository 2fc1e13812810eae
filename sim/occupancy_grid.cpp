#include "sim/occupancy_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bim/column.hpp"
#include "bim/distance_transform.hpp"
#include "bim/facade.hpp"
#include "bim/plan_geometry.hpp"
#include "bim/polygon.hpp"
#include "bim/stairs.hpp"
#include "worlds/as_built.hpp"

namespace isg::sim {

namespace {

std::vector<Eigen::Vector2d> rectangle(const Eigen::Vector2d& centre, const Eigen::Vector2d& axis,
                                       double half_length, double half_width) {
  const Eigen::Vector2d u = axis * half_length;
  const Eigen::Vector2d v = Eigen::Vector2d(-axis.y(), axis.x()) * half_width;
  return {centre - u - v, centre + u - v, centre + u + v, centre - u + v};
}

}  // namespace

void OccupancyGrid::paint(const std::vector<Eigen::Vector2d>& polygon, bool blocked) {
  // Scanline fill with exactly bim::containsPoint's rule at each cell centre (the same crossing
  // formula, and the same "within 1e-9 of an edge is inside"), in time proportional to the cells
  // and crossings instead of cells × vertices: an outline of 10^5 vertices stays cheap.
  Eigen::Vector2d lo = polygon[0], hi = polygon[0];
  for (const auto& p : polygon) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector2i a = cellOf(lo).cwiseMax(0);
  const Eigen::Vector2i b = cellOf(hi).cwiseMin(Eigen::Vector2i(width_ - 1, height_ - 1));
  if (a.x() > b.x() || a.y() > b.y()) return;
  const int rows = b.y() - a.y() + 1;
  const std::size_t n = polygon.size();
  auto row_y = [&](int y) { return centreOf({a.x(), y}).y(); };
  // The rows whose centre y lies in [y0, y1], clamped to the painted range.
  auto rows_between = [&](double y0, double y1) {
    const int first = std::max(a.y(), int(std::floor((y0 - origin_.y()) / resolution_ - 0.5)) - 1);
    const int last = std::min(b.y(), int(std::ceil((y1 - origin_.y()) / resolution_ - 0.5)) + 1);
    return std::make_pair(first, last);
  };

  std::vector<std::vector<double>> crossings(static_cast<std::size_t>(rows));
  std::vector<char> on_edge(std::size_t(rows) * std::size_t(b.x() - a.x() + 1), 0);
  constexpr double kOnEdge = 1e-9;
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Eigen::Vector2d& p = polygon[i];
    const Eigen::Vector2d& q = polygon[j];
    const auto [first, last] =
        rows_between(std::min(p.y(), q.y()) - kOnEdge, std::max(p.y(), q.y()) + kOnEdge);
    for (int y = first; y <= last; ++y) {
      const double cy = row_y(y);
      if ((p.y() > cy) != (q.y() > cy)) {
        crossings[std::size_t(y - a.y())].push_back(p.x() + (cy - p.y()) * (q.x() - p.x()) /
                                                                (q.y() - p.y()));
      }
      // Centres within kOnEdge of the edge count as inside: find them among the cells the edge
      // passes at this row's height.
      double x0 = std::min(p.x(), q.x());
      double x1 = std::max(p.x(), q.x());
      if (std::abs(q.y() - p.y()) > kOnEdge) {
        const double t0 = std::clamp((cy - kOnEdge - p.y()) / (q.y() - p.y()), 0.0, 1.0);
        const double t1 = std::clamp((cy + kOnEdge - p.y()) / (q.y() - p.y()), 0.0, 1.0);
        x0 = std::min(p.x() + t0 * (q.x() - p.x()), p.x() + t1 * (q.x() - p.x()));
        x1 = std::max(p.x() + t0 * (q.x() - p.x()), p.x() + t1 * (q.x() - p.x()));
      }
      const int cx0 = std::max(a.x(), cellOf({x0 - kOnEdge, cy}).x() - 1);
      const int cx1 = std::min(b.x(), cellOf({x1 + kOnEdge, cy}).x() + 1);
      for (int x = cx0; x <= cx1; ++x) {
        if (bim::distanceToSegment(centreOf({x, y}), p, q) < kOnEdge) {
          on_edge[std::size_t(y - a.y()) * std::size_t(b.x() - a.x() + 1) +
                  std::size_t(x - a.x())] = 1;
        }
      }
    }
  }
  for (int y = a.y(); y <= b.y(); ++y) {
    auto& xs = crossings[std::size_t(y - a.y())];
    std::sort(xs.begin(), xs.end());
    // Inside when an odd number of crossings lie strictly right of the centre.
    std::size_t right_from = 0;  // first crossing > cx
    for (int x = a.x(); x <= b.x(); ++x) {
      const double cx = centreOf({x, y}).x();
      while (right_from < xs.size() && !(xs[right_from] > cx)) ++right_from;
      const bool inside =
          ((xs.size() - right_from) % 2 == 1) ||
          on_edge[std::size_t(y - a.y()) * std::size_t(b.x() - a.x() + 1) + std::size_t(x - a.x())];
      if (inside) blocked_[std::size_t(index({x, y}))] = blocked;
    }
  }
}

OccupancyGrid::OccupancyGrid(const bim::Plan& plan, const bim::AsBuilt& as_built,
                             const std::string& level_id, double resolution)
    : resolution_(resolution), asked_resolution_(resolution) {
  const bim::Level& plan_level = *plan.findLevel(level_id);
  const bim::Level level = worlds::asBuiltLevel(plan_level, as_built);
  const bim::LevelGeometry geometry = bim::computeLevelGeometry(level);
  frame(level, geometry, resolution);
  for (const auto& room : level.rooms) {
    paint(room.outline, false);
  }
  // An open floor (no rooms, or rooms covering little of it): its inside is its façade's outline.
  const bool open_floor = bim::isOpenFloor(level);
  if (open_floor) paint(bim::facadeOutline(level), false);
  clearPlannedWalls(plan_level, as_built);
  // A wall blocks where it stands lower than the robot can pass under.
  constexpr double kRobotHeight = 0.9;
  for (const auto& g : geometry.walls) {
    if (g.wall->base > kRobotHeight) continue;
    const auto footprint = g.footprint();
    paint(footprint, true);
  }
  for (const auto& column : level.columns) {  // rectangular ones are among the walls already
    if (column.round() && column.base <= kRobotHeight) paint(bim::columnFootprint(column), true);
  }
  for (const auto& door : level.doors) {
    const bool closed = std::find(as_built.closed_doors.begin(), as_built.closed_doors.end(),
                                  door.id) != as_built.closed_doors.end();
    const bool to_outside = door.rooms[0] == bim::kOutside || door.rooms[1] == bim::kOutside;
    if (closed || (to_outside && !open_floor)) continue;
    const bim::WallGeometry& g = *geometry.findWall(door.wall);
    const auto opening = rectangle(g.pointAt(door.offset), g.axis, 0.5 * door.width,
                                   0.5 * g.wall->thickness + resolution_);
    paint(opening, false);
  }
  paintFlights(plan, plan_level);
  for (const auto& c : as_built.clutter) {
    if (c.level != level_id) continue;
    const auto box = rectangle(c.center.head<2>(), {std::cos(c.yaw), std::sin(c.yaw)},
                               0.5 * c.size.x(), 0.5 * c.size.y());
    paint(box, true);
  }
  // Clearance: exact Euclidean distance to the nearest blocked cell.
  const std::vector<double> field = bim::squaredDistanceTransform(blocked_, width_, height_);
  clearance_.resize(field.size());
  for (std::size_t i = 0; i < field.size(); ++i) {
    // Centre-to-centre distances can overstate the distance from a point of this cell to the
    // obstacle's true surface by up to one cell diagonal: subtract it, so the clearance is a
    // lower bound everywhere in the cell.
    const double d = std::sqrt(field[i]) * resolution_ - std::sqrt(2.0) * resolution_;
    clearance_[i] = float(std::max(0.0, d));
  }
}

void OccupancyGrid::frame(const bim::Level& level, const bim::LevelGeometry& geometry,
                          double resolution) {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& g : geometry.walls) {
    for (const auto& p : g.footprint()) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  for (const auto& r : level.rooms) {
    for (const auto& p : r.outline) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  for (const auto& column : level.columns) {
    for (const auto& p : bim::columnFootprint(column)) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  // A very large level gets coarser cells rather than gigabytes of grid (docs/simulation.md).
  const Eigen::Vector2d span = hi - lo;
  const double cells = (span.x() / resolution + 6) * (span.y() / resolution + 6);
  if (cells > kMaxCells) resolution_ = resolution * std::sqrt(cells / kMaxCells);
  origin_ = lo - Eigen::Vector2d::Constant(2 * resolution_);
  width_ = int(std::ceil((hi.x() - origin_.x()) / resolution_)) + 2;
  height_ = int(std::ceil((hi.y() - origin_.y()) / resolution_)) + 2;
  blocked_.assign(std::size_t(width_) * height_, 1);
}

void OccupancyGrid::clearPlannedWalls(const bim::Level& plan_level, const bim::AsBuilt& as_built) {
  // Where a wall of the plan is missing in the building, its footprint is floor: the rooms on
  // either side join, as in the world (and so where it is built only in part, between its parts).
  // Where it is shifted or turned, the part of its planned footprint it left is floor too: left
  // blocked, that strip would lie across each of its doorways and shut them. (Walls as they stand
  // are painted over it.)
  const bim::LevelGeometry plan_geometry = bim::computeLevelGeometry(plan_level);
  for (const auto& g : plan_geometry.walls) {
    const std::string& id = g.wall->id;
    const bool missing = std::find(as_built.missing_walls.begin(), as_built.missing_walls.end(),
                                   id) != as_built.missing_walls.end();
    const bool shifted =
        std::any_of(as_built.wall_shifts.begin(), as_built.wall_shifts.end(),
                    [&](const bim::WallShift& s) { return s.wall == id && s.offset != 0; });
    const bool turned =
        std::any_of(as_built.wall_rotations.begin(), as_built.wall_rotations.end(),
                    [&](const bim::WallRotation& r) { return r.wall == id && r.angle_deg != 0; });
    const bool shortened =
        std::any_of(as_built.shortened_walls.begin(), as_built.shortened_walls.end(),
                    [&](const bim::ShortenedWall& w) { return w.wall == id; });
    if (missing || shifted || turned || shortened) paint(g.footprint(), false);
  }
}

void OccupancyGrid::paintFlights(const bim::Plan& plan, const bim::Level& plan_level) {
  // Flights of stairs are no floor to walk on for a route on one level: below, the steps stand
  // there; above, the stairwell is open over the box of the flight's upper part (as the world
  // opens it). A route that changes level walks the flight itself (sim/route_planner.cpp).
  for (const auto& from : plan.levels) {
    for (const auto& stair : from.stairs) {
      const bim::Level* to = plan.findLevel(stair.to);
      if (to == nullptr || (&from != &plan_level && to != &plan_level)) continue;
      const bim::StairGeometry g = bim::computeStairGeometry(stair, from, *to);
      const bool upper = plan_level.elevation > std::min(from.elevation, to->elevation);
      if (!upper) {
        paint(g.footprint(), true);
        continue;
      }
      const bim::Box2 box = bim::Box2::around(g.openingFootprint());
      paint({box.lo, {box.hi.x(), box.lo.y()}, box.hi, {box.lo.x(), box.hi.y()}}, true);
    }
  }
}

Eigen::Vector2i OccupancyGrid::cellOf(const Eigen::Vector2d& p) const {
  const Eigen::Vector2d q = (p - origin_) / resolution_;
  return {int(std::floor(q.x())), int(std::floor(q.y()))};
}

Eigen::Vector2d OccupancyGrid::centreOf(const Eigen::Vector2i& c) const {
  return origin_ + resolution_ * (c.cast<double>() + Eigen::Vector2d::Constant(0.5));
}

}  // namespace isg::sim
