#pragma once

// Angles in the plane, defined once for every module: yaws, headings and their differences.
#include <Eigen/Core>
#include <cmath>
#include <numbers>

namespace isg::common {

// a wrapped to [−π, π] (std::remainder: a half turn keeps its sign).
inline double wrapAngle(double a) { return std::remainder(a, 2.0 * std::numbers::pi); }

// a − b wrapped to (−π, π]: a half turn is always +π, so a filter that averages differences never
// sees one turn with two signs.
inline double angleDifference(double a, double b) {
  double d = wrapAngle(a - b);
  if (d <= -std::numbers::pi) d += 2.0 * std::numbers::pi;
  return d;
}

// Degrees for people (files, logs, options), radians for the maths.
inline constexpr double degrees(double radians) { return radians * 180.0 / std::numbers::pi; }
inline constexpr double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

// The heading of a direction in the plane.
inline double headingOf(const Eigen::Vector2d& direction) {
  return std::atan2(direction.y(), direction.x());
}

// The yaw of a rotation: the heading of its x axis (the yaw of a base whose roll and pitch are
// small).
inline double yawOf(const Eigen::Matrix3d& R) { return std::atan2(R(1, 0), R(0, 0)); }

}  // namespace isg::common
