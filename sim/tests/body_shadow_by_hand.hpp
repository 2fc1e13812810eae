#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "sim/robot_model.hpp"
#include "sim/vlp16.hpp"

namespace isg::sim::by_hand {

// Whether the body stops a laser's firing at an azimuth (in L), worked out apart from the
// simulator: from a sensor above the body's footprint, a ray going down meets the body iff it
// crosses the plane of the body's top inside the top's rectangle (outside it, it only goes
// further out).
inline bool blockedByTheTop(const Eigen::Isometry3d& R_T_L, int laser, double azimuth) {
  const RobotBox body = robotBodyBox();
  const double elevation = Vlp16::kElevationDeg[laser] * std::numbers::pi / 180.0;
  if (elevation >= 0) return false;
  const Eigen::Vector3d origin = R_T_L * Vlp16::origin(laser);
  const double drop = origin.z() - (body.centre.z() + body.half.z());
  const double reach = drop / std::tan(-elevation);
  const double x = origin.x() + reach * std::cos(azimuth);
  const double y = origin.y() + reach * std::sin(azimuth);
  return std::abs(x - body.centre.x()) <= body.half.x() &&
         std::abs(y - body.centre.y()) <= body.half.y();
}

// The firing sequence of a point of `laser`, from its time from the turn's first firing.
inline int sequenceOf(double time_from_first_firing, int laser) {
  return int(std::lround((time_from_first_firing - laser * Vlp16::kFiringInterval) /
                         Vlp16::kSequenceDuration));
}

}  // namespace isg::sim::by_hand
