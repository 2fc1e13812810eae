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

Eigen::Isometry3d trueStartB_T_M(const SensorStreams& streams) {
  if (streams.ground_truth.empty()) return Eigen::Isometry3d::Identity();
  if (streams.odometry.empty()) {
    // The odometry the LiDAR and the IMU make (slam::ScanOdometry) starts at the base's first
    // pose, levelled: M is that pose's position and heading, its z up.
    const Eigen::Isometry3d B_T_R = streams.ground_truth.front().pose;
    Eigen::Isometry3d B_T_M = Eigen::Isometry3d::Identity();
    B_T_M.linear() = Eigen::AngleAxisd(common::yawOf(B_T_R.linear()), Eigen::Vector3d::UnitZ())
                         .toRotationMatrix();
    B_T_M.translation() = B_T_R.translation();
    return B_T_M;
  }
  return streams.ground_truth.front().pose * streams.odometry.front().pose.inverse();
}

}  // namespace isg::sensors
