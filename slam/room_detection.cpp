#include "slam/room_detection.hpp"

#include <cmath>
#include <limits>

#include "bim/agraph.hpp"

namespace isg::slam {

namespace {

struct Side {
  int plane = -1;
  double distance = std::numeric_limits<double>::infinity();
};

// The nearest wall in front of the point on each side of a direction u (normal ≈ +u faces the
// point from behind it, normal ≈ -u from ahead of it).
std::array<Side, 2> nearestPair(const Eigen::Vector2d& point, const std::vector<MapPlane>& planes,
                                const Eigen::Vector2d& u, double min_cos) {
  std::array<Side, 2> sides;
  for (int i = 0; i < int(planes.size()); ++i) {
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
    if (distance < sides[side].distance) sides[side] = {i, distance};
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
  const double min_cos = std::cos(options.axis_tolerance_deg * M_PI / 180.0);
  const Eigen::Vector2d ux(std::cos(dominant_yaw), std::sin(dominant_yaw));
  const Eigen::Vector2d uy(-ux.y(), ux.x());
  const auto x = nearestPair(point, planes, ux, min_cos);
  const auto y = nearestPair(point, planes, uy, min_cos);
  auto valid = [&](const std::array<Side, 2>& p) {
    if (p[0].plane < 0 || p[1].plane < 0) return false;
    const double width = p[0].distance + p[1].distance;
    return width >= options.min_width && width <= options.max_width;
  };
  const bool has_x = valid(x), has_y = valid(y);
  if (!has_x && !has_y) return std::nullopt;

  RoomCandidate room;
  if (has_x && has_y) {
    // The rectangle's sides: x-walls span the y range and y-walls the x range.
    const double x_lo = ux.dot(point) - x[0].distance, x_hi = ux.dot(point) + x[1].distance;
    const double y_lo = uy.dot(point) - y[0].distance, y_hi = uy.dot(point) + y[1].distance;
    const bool covered = coverage(planes[x[0].plane], uy, y_lo, y_hi) >= options.min_coverage &&
                         coverage(planes[x[1].plane], uy, y_lo, y_hi) >= options.min_coverage &&
                         coverage(planes[y[0].plane], ux, x_lo, x_hi) >= options.min_coverage &&
                         coverage(planes[y[1].plane], ux, x_lo, x_hi) >= options.min_coverage;
    const double wx = x[0].distance + x[1].distance, wy = y[0].distance + y[1].distance;
    const bool corridor_shape =
        std::max(wx, wy) >= options.corridor_min_length_ratio * std::min(wx, wy) &&
        std::min(wx, wy) <= 3.0;
    if (covered && !corridor_shape) {
      room.four_wall = true;
      room.pairs = {{{x[0].plane, x[1].plane}, {y[0].plane, y[1].plane}}};
      room.widths = {wx, wy};
      room.centre = bim::fourWallRoomCentre(planes[x[0].plane].plane, planes[x[1].plane].plane,
                                            planes[y[0].plane].plane, planes[y[1].plane].plane);
      return room;
    }
  }
  // A corridor: the narrower valid pair, whose walls are long compared with the gap between them.
  const bool use_x =
      has_x && (!has_y || x[0].distance + x[1].distance <= y[0].distance + y[1].distance);
  const auto& pair = use_x ? x : y;
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
