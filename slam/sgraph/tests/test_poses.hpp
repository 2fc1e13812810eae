#pragma once

// A pose for factor tests: at (x, y, z), turned by yaw about z, then pitched about y — enough to
// test that planar factors ignore what they should (height, a small pitch).

#include <Eigen/Geometry>

namespace isg::testing {

inline Eigen::Isometry3d pose(double x, double y, double z, double yaw, double pitch = 0.0) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x, y, z);
  T.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()))
                   .toRotationMatrix();
  return T;
}

}  // namespace isg::testing
