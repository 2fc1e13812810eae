#pragma once

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

namespace isg::slam {

// The normal of the plane a neighbourhood of points lies on, from their covariance (any scale:
// only the eigenvalues' shares count), or zero when they are not a plane: a plane is thin across
// (the smallest eigenvalue's share at most max_planarity) and spread both ways within it (the
// middle one's at least min_spread). Points along one ring of a LiDAR are a line, whose "normal"
// would be any direction across it. Shared by the S-Graph's local map and the odometry's voxel
// map, so that both call the same thing a plane.
inline Eigen::Vector3d planeNormalOf(const Eigen::Matrix3d& covariance, double max_planarity,
                                     double min_spread) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  const Eigen::Vector3d values = solver.eigenvalues();
  const double total = values.sum();
  if (total <= 0.0 || values(0) / total > max_planarity || values(1) / total < min_spread) {
    return Eigen::Vector3d::Zero();
  }
  return solver.eigenvectors().col(0).normalized();
}

}  // namespace isg::slam
