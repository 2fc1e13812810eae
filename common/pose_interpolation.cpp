#include "common/pose_interpolation.hpp"

#include <algorithm>

namespace isg::common {

std::optional<Eigen::Isometry3d> interpolatePose(const Trajectory& trajectory, double t) {
  if (trajectory.empty() || t < trajectory.front().t - 1e-9 || t > trajectory.back().t + 1e-9) {
    return std::nullopt;
  }
  const auto hi = std::lower_bound(trajectory.begin(), trajectory.end(), t,
                                   [](const StampedPose& p, double time) { return p.t < time; });
  if (hi == trajectory.begin()) return trajectory.front().pose;
  if (hi == trajectory.end()) return trajectory.back().pose;
  const auto lo = hi - 1;
  const double s = hi->t > lo->t ? std::clamp((t - lo->t) / (hi->t - lo->t), 0.0, 1.0) : 0.0;
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = Eigen::Quaterniond(lo->pose.linear())
                     .slerp(s, Eigen::Quaterniond(hi->pose.linear()))
                     .toRotationMatrix();
  out.translation() = (1.0 - s) * lo->pose.translation() + s * hi->pose.translation();
  return out;
}

}  // namespace isg::common
