#include "sensors/mount_transform.hpp"

#include <algorithm>
#include <cmath>

namespace isg::sensors {

Eigen::Isometry3d mountTransform(const std::array<double, 6>& m) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(m[0], m[1], m[2]);
  T.linear() = (Eigen::AngleAxisd(m[5], Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(m[4], Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(m[3], Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return T;
}

std::array<double, 6> mountXyzRpy(const Eigen::Isometry3d& T) {
  const Eigen::Matrix3d R = T.linear();
  const Eigen::Vector3d t = T.translation();
  const double pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  // At ±90° of pitch the x axis is vertical and only yaw ∓ roll is defined: roll 0, all of it
  // yaw (Rz(yaw)·Ry(±90°) has R(0,1) = −sin(yaw), R(1,1) = cos(yaw)).
  if (std::abs(R(2, 0)) > 1.0 - 1e-12) {
    return {t.x(), t.y(), t.z(), 0.0, pitch, std::atan2(-R(0, 1), R(1, 1))};
  }
  const double roll = std::atan2(R(2, 1), R(2, 2));
  const double yaw = std::atan2(R(1, 0), R(0, 0));
  return {t.x(), t.y(), t.z(), roll, pitch, yaw};
}

}  // namespace isg::sensors
