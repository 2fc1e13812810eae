#include "sensors/sensor_streams.hpp"

namespace isg::sensors {

void quantiseStreams(SensorStreams& streams) {
  streams.ground_truth = eval::quantised(streams.ground_truth);
  streams.odometry = eval::quantised(streams.odometry);
  for (double& t : streams.scan_stamps) t = eval::quantisedTime(t);
}

Eigen::Isometry3d trueStartB_T_M(const SensorStreams& streams) {
  if (streams.ground_truth.empty() || streams.odometry.empty()) {
    return Eigen::Isometry3d::Identity();
  }
  return streams.ground_truth.front().pose * streams.odometry.front().pose.inverse();
}

}  // namespace isg::sensors
