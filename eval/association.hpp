#pragma once

#include <vector>

#include "common/pose_track.hpp"
#include "common/tum.hpp"

namespace isg::eval {

// Pairs of poses that describe the same instant, as evo associates them
// (evo.core.sync.associate_trajectories): for each stamp of the shorter trajectory (the
// estimate when both are as long), the nearest stamp of the longer one — the first on a tie —
// kept when within `max_diff` seconds. No interpolation; a pose of the longer trajectory may be
// used twice.
struct Association {
  std::vector<int> reference;  // indices into the reference trajectory
  std::vector<int> estimate;   // indices into the estimated trajectory, same length
};

Association associate(common::PoseSequence reference, common::PoseSequence estimate,
                      double max_diff = 0.01);

}  // namespace isg::eval
