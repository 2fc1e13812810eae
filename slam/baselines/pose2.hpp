#pragma once

#include <Eigen/Geometry>
#include <cmath>

#include "common/angles.hpp"

namespace isg::slam {

// A pose in the plane: what 2D localizers (AMCL) estimate.
struct Pose2 {
  double x = 0.0;
  double y = 0.0;
  double yaw = 0.0;

  Eigen::Vector2d position() const { return {x, y}; }
  // A point of this pose's frame in the parent frame.
  Eigen::Vector2d apply(const Eigen::Vector2d& p) const {
    const double c = std::cos(yaw), s = std::sin(yaw);
    return {x + c * p.x() - s * p.y(), y + s * p.x() + c * p.y()};
  }
};

// The planar part of a 3D pose: x, y and the heading of its x axis.
inline Pose2 planarPose(const Eigen::Isometry3d& T) {
  return {T.translation().x(), T.translation().y(), common::yawOf(T.linear())};
}

// A planar pose as a 3D transform (a turn about z, then x, y and the given z).
inline Eigen::Isometry3d toIsometry(const Pose2& p, double z = 0.0) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(p.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(p.x, p.y, z);
  return T;
}

}  // namespace isg::slam
