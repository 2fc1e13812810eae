#include "slam/isgraph/flight_footprints.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace isg::slam {

double FlightFootprint::distance(const Eigen::Vector2d& p) const {
  const Eigen::Vector2d axis = top - bottom;
  const double length = axis.norm();
  if (length < 1e-9) return std::max(0.0, (p - bottom).norm() - half_width);
  const Eigen::Vector2d along = axis / length;
  const Eigen::Vector2d across(-along.y(), along.x());
  const double s = (p - bottom).dot(along);
  const double outside_along = std::max({0.0, -s, s - length});
  const double outside_across = std::max(0.0, std::abs((p - bottom).dot(across)) - half_width);
  return std::hypot(outside_along, outside_across);
}

bool FlightFootprint::joins(double elevation, double tolerance) const {
  return std::abs(z_low - elevation) <= tolerance || std::abs(z_high - elevation) <= tolerance;
}

std::vector<FlightFootprint> flightFootprints(const bim::AGraph& plan) {
  struct Sides {
    const bim::WallSurfaceNode* left = nullptr;
    const bim::WallSurfaceNode* right = nullptr;
  };
  std::map<std::string, Sides> by_stair;
  for (const auto& surface : plan.surfaces) {
    if (surface.stair.empty() || surface.segments.empty()) continue;
    if (surface.id == surface.stair + ":stair-left") by_stair[surface.stair].left = &surface;
    if (surface.id == surface.stair + ":stair-right") by_stair[surface.stair].right = &surface;
  }
  std::vector<FlightFootprint> out;
  for (const auto& [stair, sides] : by_stair) {
    if (sides.left == nullptr || sides.right == nullptr) continue;
    const auto& [left_a, left_b] = sides.left->segments.front();
    const auto& [right_a, right_b] = sides.right->segments.front();
    FlightFootprint footprint;
    footprint.stair = stair;
    footprint.bottom = 0.5 * (left_a + right_a);
    footprint.top = 0.5 * (left_b + right_b);
    footprint.half_width = 0.5 * (left_a - right_a).norm();
    footprint.z_low = sides.left->z_min;
    footprint.z_high = sides.left->z_max;
    out.push_back(footprint);
  }
  return out;
}

}  // namespace isg::slam
