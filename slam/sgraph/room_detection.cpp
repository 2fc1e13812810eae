#include "slam/sgraph/room_detection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "bim/agraph.hpp"

namespace isg::slam {

namespace {

struct Side {
  int plane = -1;
  double distance = std::numeric_limits<double>::infinity();
};

// The walls in front of the point on each side of a direction u (normal ≈ +u faces the point from
// behind it, normal ≈ -u from ahead of it), nearest first, at most `keep` a side. Clutter standing
// before a wall comes first; the caller tries the next ones.
std::array<std::vector<Side>, 2> wallsAround(const Eigen::Vector2d& point,
                                             const std::vector<MapPlane>& planes,
                                             const Eigen::Vector2d& u, double min_cos,
                                             double min_height, std::size_t keep = 3) {
  std::array<std::vector<Side>, 2> sides;
  for (int i = 0; i < int(planes.size()); ++i) {
    if (!seenAsWall(planes[i], min_height)) continue;
    const Eigen::Vector2d n = planes[i].plane.normal.head<2>();
    const double c = n.dot(u);
    const int side = c >= min_cos ? 0 : (c <= -min_cos ? 1 : -1);
    if (side < 0) continue;
    const double distance = planes[i].plane.signedDistance({point.x(), point.y(), 1.0});
    if (distance <= 0) continue;  // the point is behind this wall
    // The wall must run past the point: its extent covers the point's projection (with 0.5 m).
    const Eigen::Vector2d along(-n.y(), n.x());
    const double s = along.dot(point);
    const double a = along.dot(planes[i].start), b = along.dot(planes[i].end);
    if (s < std::min(a, b) - 0.5 || s > std::max(a, b) + 0.5) continue;
    sides[side].push_back({i, distance});
  }
  for (auto& list : sides) {
    std::sort(list.begin(), list.end(),
              [](const Side& a, const Side& b) { return a.distance < b.distance; });
    if (list.size() > keep) list.resize(keep);
  }
  return sides;
}

// How much of [lo, hi] along `along` a wall's observed extent covers, as a share.
double coverage(const MapPlane& wall, const Eigen::Vector2d& along, double lo, double hi) {
  const double a = std::min(along.dot(wall.start), along.dot(wall.end));
  const double b = std::max(along.dot(wall.start), along.dot(wall.end));
  return std::max(0.0, std::min(hi, b) - std::max(lo, a)) / std::max(hi - lo, 1e-9);
}

double extentLength(const MapPlane& wall) { return (wall.end - wall.start).norm(); }

}  // namespace

std::optional<RoomCandidate> detectRoom(const Eigen::Vector2d& point,
                                        const std::vector<MapPlane>& planes, double dominant_yaw,
                                        const RoomDetectionOptions& options) {
  const double min_cos = std::cos(options.axis_tolerance_deg * std::numbers::pi / 180.0);
  const Eigen::Vector2d ux(std::cos(dominant_yaw), std::sin(dominant_yaw));
  const Eigen::Vector2d uy(-ux.y(), ux.x());
  const auto xs = wallsAround(point, planes, ux, min_cos, options.min_wall_height);
  const auto ys = wallsAround(point, planes, uy, min_cos, options.min_wall_height);
  auto valid = [&](const Side& a, const Side& b) {
    const double width = a.distance + b.distance;
    return width >= options.min_width && width <= options.max_width;
  };
  // The nearest valid pair on each axis (what a corridor is made of).
  auto nearest =
      [&](const std::array<std::vector<Side>, 2>& sides) -> std::optional<std::array<Side, 2>> {
    if (sides[0].empty() || sides[1].empty() || !valid(sides[0][0], sides[1][0]))
      return std::nullopt;
    return std::array<Side, 2>{sides[0][0], sides[1][0]};
  };
  const auto x = nearest(xs), y = nearest(ys);
  if (!x && !y && (xs[0].empty() || xs[1].empty()) && (ys[0].empty() || ys[1].empty())) {
    return std::nullopt;
  }

  RoomCandidate room;
  // Four-wall rooms: the smallest rectangle, over the few nearest walls on each side, whose
  // walls' observed extents cover its sides.
  double best_area = std::numeric_limits<double>::infinity();
  for (const Side& x0 : xs[0]) {
    for (const Side& x1 : xs[1]) {
      if (!valid(x0, x1)) continue;
      for (const Side& y0 : ys[0]) {
        for (const Side& y1 : ys[1]) {
          if (!valid(y0, y1)) continue;
          const double wx = x0.distance + x1.distance, wy = y0.distance + y1.distance;
          if (wx * wy >= best_area) continue;
          const double x_lo = ux.dot(point) - x0.distance, x_hi = ux.dot(point) + x1.distance;
          const double y_lo = uy.dot(point) - y0.distance, y_hi = uy.dot(point) + y1.distance;
          const bool covered = coverage(planes[x0.plane], uy, y_lo, y_hi) >= options.min_coverage &&
                               coverage(planes[x1.plane], uy, y_lo, y_hi) >= options.min_coverage &&
                               coverage(planes[y0.plane], ux, x_lo, x_hi) >= options.min_coverage &&
                               coverage(planes[y1.plane], ux, x_lo, x_hi) >= options.min_coverage;
          const bool corridor_shape =
              std::max(wx, wy) >= options.corridor_min_length_ratio * std::min(wx, wy) &&
              std::min(wx, wy) <= 3.0;
          if (!covered || corridor_shape) continue;
          best_area = wx * wy;
          room.four_wall = true;
          room.pairs = {{{x0.plane, x1.plane}, {y0.plane, y1.plane}}};
          room.widths = {wx, wy};
        }
      }
    }
  }
  if (room.four_wall) {
    room.centre =
        bim::fourWallRoomCentre(planes[room.pairs[0][0]].plane, planes[room.pairs[0][1]].plane,
                                planes[room.pairs[1][0]].plane, planes[room.pairs[1][1]].plane);
    return room;
  }
  const bool has_x = x.has_value(), has_y = y.has_value();
  if (!has_x && !has_y) return std::nullopt;
  // A corridor: the narrower valid pair, whose walls are long compared with the gap between them.
  const bool use_x = has_x && (!has_y || (*x)[0].distance + (*x)[1].distance <=
                                             (*y)[0].distance + (*y)[1].distance);
  const std::array<Side, 2>& pair = use_x ? *x : *y;
  const double width = pair[0].distance + pair[1].distance;
  const double length =
      std::min(extentLength(planes[pair[0].plane]), extentLength(planes[pair[1].plane]));
  if (length < options.corridor_min_length_ratio * width || width > 3.5) return std::nullopt;
  room.four_wall = false;
  room.pairs[0] = {pair[0].plane, pair[1].plane};
  room.widths = {width, 0.0};
  room.centre =
      bim::twoWallRoomCentre(planes[pair[0].plane].plane, planes[pair[1].plane].plane, point);
  return room;
}

}  // namespace isg::slam
