#pragma once

// Angles in the plane, defined once for every module: yaws, headings and their differences.
#include <Eigen/Core>
#include <cmath>
#include <numbers>

namespace isg::common {

// std::remainder(x, period) for period > 0, exactly, without glibc's slow general path (the graph
// matcher wraps angles millions of times a run; std::remainder was a tenth of a large building's
// run). The quotient rounded to the nearest integer, ties to even; then x − n·period in one fused
// multiply-add, which is exact because the true remainder is a representable double. When x/period
// rounded the wrong way near a tie, the neighbouring quotient is taken.
inline double remainderOf(double x, double period) {
  if (!(std::abs(x) < 1e9 * period)) return std::remainder(x, period);  // huge, infinite, NaN
  double n = std::nearbyint(x / period);
  double r = std::fma(-n, period, x);
  const double half = 0.5 * period;
  if (std::abs(r) > half || (std::abs(r) == half && std::fmod(n, 2.0) != 0.0)) {
    n += r > 0 ? 1.0 : -1.0;
    r = std::fma(-n, period, x);
  }
  return r == 0.0 ? std::copysign(0.0, x) : r;  // a zero remainder has x's sign
}

// a wrapped to [−π, π] (as std::remainder: a half turn keeps its sign).
inline double wrapAngle(double a) { return remainderOf(a, 2.0 * std::numbers::pi); }

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
