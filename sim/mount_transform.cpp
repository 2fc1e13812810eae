#include "sim/mount_transform.hpp"

namespace isg::sim {

Eigen::Isometry3d mountTransform(const std::array<double, 6>& m) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(m[0], m[1], m[2]);
  T.linear() = (Eigen::AngleAxisd(m[5], Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(m[4], Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(m[3], Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return T;
}

}  // namespace isg::sim
