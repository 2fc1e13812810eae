#pragma once

#include <Eigen/Geometry>
#include <optional>

#include "common/pose_track.hpp"

namespace isg::common {

// The pose at `t` between the rows of a time-ordered trajectory: positions linear, rotations
// slerped; nullopt outside its span (a nanosecond of slack at either end).
std::optional<Eigen::Isometry3d> interpolatePose(PoseSequence trajectory, double t);

}  // namespace isg::common
