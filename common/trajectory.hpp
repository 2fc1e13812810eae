#pragma once

#include <Eigen/Geometry>
#include <vector>

namespace isg::common {

// A pose at a time, and a trajectory of them in time order: what ground truth, odometry and every
// estimate are, and what a TUM file holds (common/tum.hpp).
struct StampedPose {
  double t = 0.0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};
using Trajectory = std::vector<StampedPose>;

}  // namespace isg::common
