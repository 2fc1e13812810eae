#pragma once

#include <Eigen/Geometry>
#include <vector>

namespace isg::eval {

// A similarity transform x ↦ s·R·x + t.
struct Similarity {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  double scale = 1.0;

  Eigen::Vector3d apply(const Eigen::Vector3d& x) const {
    return scale * rotation * x + translation;
  }
  // Applied to a pose: position scaled, rotated and moved; orientation rotated.
  Eigen::Isometry3d apply(const Eigen::Isometry3d& pose) const;
};

// Umeyama's least-squares alignment of `from` onto `to` (1991), as evo computes it
// (evo.core.geometry.umeyama_alignment): SE(3) without scale, Sim(3) with. Throws
// std::invalid_argument when there are fewer than 3 points or they are degenerate.
Similarity umeyama(const std::vector<Eigen::Vector3d>& from, const std::vector<Eigen::Vector3d>& to,
                   bool with_scale);

}  // namespace isg::eval
