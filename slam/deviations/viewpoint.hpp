#pragma once

#include <Eigen/Core>

#include "slam/sight_profile.hpp"

namespace isg::slam {

// Where the sensor stood for a keyframe, placed in the plan: what the deviation report asks what
// was in view of, and what was seen past.
struct Viewpoint {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // the sensor's, in B
  double yaw = 0.0;                                    // the base's heading in B (rad)
  const SightProfile* sight = nullptr;                 // null or empty: not recorded
  bool hasSight() const { return sight != nullptr && !sight->empty(); }
};

}  // namespace isg::slam
