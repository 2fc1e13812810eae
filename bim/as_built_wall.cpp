#include "bim/as_built_wall.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "bim/polygon.hpp"

namespace isg::bim {

double rotationPivotAlong(const Wall& planned, const WallRotation& rotation) {
  const double length = (planned.end - planned.start).norm();
  switch (rotation.about) {
    case WallRotation::About::kStart:
      return 0.0;
    case WallRotation::About::kEnd:
      return length;
    case WallRotation::About::kAlong:
      return rotation.along_m;
    case WallRotation::About::kCentre:
      break;
  }
  return 0.5 * length;
}

Wall builtWall(const Wall& planned, const AsBuilt& as_built) {
  Wall built = planned;
  const Eigen::Vector2d axis = (planned.end - planned.start).normalized();
  const Eigen::Vector2d left(-axis.y(), axis.x());
  for (const auto& rotation : as_built.wall_rotations) {
    if (rotation.wall != planned.id) continue;
    const Eigen::Vector2d pivot = planned.start + rotationPivotAlong(planned, rotation) * axis;
    const Eigen::Rotation2Dd turn(rotation.angle_deg * std::numbers::pi / 180.0);
    built.start = pivot + turn * (planned.start - pivot);
    built.end = pivot + turn * (planned.end - pivot);
  }
  for (const auto& shift : as_built.wall_shifts) {
    if (shift.wall != planned.id) continue;
    built.start += shift.offset * left;
    built.end += shift.offset * left;
  }
  return built;
}

AxisDeviation axisDeviation(const Wall& planned, const Eigen::Vector2d& built_point,
                            const Eigen::Vector2d& built_direction) {
  const Eigen::Vector2d axis = (planned.end - planned.start).normalized();
  const Eigen::Vector2d left(-axis.y(), axis.x());
  Eigen::Vector2d direction = built_direction.normalized();
  if (direction.dot(axis) < 0.0) direction = -direction;
  const Eigen::Vector2d centre = 0.5 * (planned.start + planned.end);
  AxisDeviation deviation;
  // The built line meets the planned centre's normal at centre + t·left.
  deviation.offset_m = cross(direction, built_point - centre) / cross(direction, left);
  deviation.angle_deg =
      std::atan2(cross(axis, direction), axis.dot(direction)) * 180.0 / std::numbers::pi;
  return deviation;
}

}  // namespace isg::bim
