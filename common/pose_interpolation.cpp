#include "common/pose_interpolation.hpp"

#include <algorithm>

namespace isg::common {

std::optional<Eigen::Isometry3d> interpolatePose(PoseSequence trajectory, double t) {
  if (trajectory.empty() || t < trajectory.time(0) - 1e-9 ||
      t > trajectory.time(trajectory.size() - 1) + 1e-9) {
    return std::nullopt;
  }
  const std::size_t first = trajectory.lowerBound(t);
  if (first == 0) return trajectory.front().pose;
  if (first == trajectory.size()) return trajectory.back().pose;
  const StampedPose lo = trajectory[first - 1], hi = trajectory[first];
  const double s = hi.t > lo.t ? std::clamp((t - lo.t) / (hi.t - lo.t), 0.0, 1.0) : 0.0;
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = Eigen::Quaterniond(lo.pose.linear())
                     .slerp(s, Eigen::Quaterniond(hi.pose.linear()))
                     .toRotationMatrix();
  out.translation() = (1.0 - s) * lo.pose.translation() + s * hi.pose.translation();
  return out;
}

}  // namespace isg::common
