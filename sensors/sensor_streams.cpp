#include "sensors/sensor_streams.hpp"

#include <cmath>

#include "common/angles.hpp"
#include "common/tum.hpp"

namespace isg::sensors {

void quantiseStreams(SensorStreams& streams) {
  for (common::PoseTrack* track : {&streams.ground_truth, &streams.odometry}) {
    common::PoseTrack rounded;
    rounded.reserve(track->size());
    for (const auto& pose : *track) rounded.pushQuantised(pose);
    *track = std::move(rounded);
  }
  for (double& t : streams.scan_stamps) t = common::quantisedTime(t);
}

Eigen::Isometry3d startB_T_M(const SensorStreams& streams, const Eigen::Isometry3d& B_T_R0) {
  if (streams.odometry.empty()) {
    // The odometry the LiDAR and the IMU make (slam::ScanOdometry) starts at the base's first
    // pose, levelled: M is that pose's position and heading, its z up.
    Eigen::Isometry3d B_T_M = Eigen::Isometry3d::Identity();
    B_T_M.linear() = Eigen::AngleAxisd(common::yawOf(B_T_R0.linear()), Eigen::Vector3d::UnitZ())
                         .toRotationMatrix();
    B_T_M.translation() = B_T_R0.translation();
    return B_T_M;
  }
  return B_T_R0 * streams.odometry.front().pose.inverse();
}

Eigen::Isometry3d trueStartB_T_M(const SensorStreams& streams) {
  if (streams.ground_truth.empty()) return Eigen::Isometry3d::Identity();
  return startB_T_M(streams, streams.ground_truth.front().pose);
}

}  // namespace isg::sensors
