#pragma once

// Shared by the tests that inject a match into the iS-Graph in the loop (contradiction_test,
// off_flight_test): the checks that would lose a wrong match switched off, so that only the path
// under test can correct it, and the true B_T_M at the start as (x, y, yaw).
#include <Eigen/Core>

#include "common/angles.hpp"
#include "sensors/sensor_streams.hpp"
#include "slam/isgraph/isgraph_localizer.hpp"

namespace isg::sim::testing {

// Every lost check but the flight check off: held correspondences never leave their gate, none
// are needed, any pose is in the building, and neither the recent map nor the plan's share of
// the scan is ever found to disagree.
inline slam::ISGraphOptions withTheLostChecksOff() {
  slam::ISGraphOptions options;
  options.hold_angle_deg = 180.0;
  options.hold_distance = 1e9;
  options.lost_min_held = 0;
  options.outside_margin = 1e9;
  options.suspect_share = 0.0;
  options.plan_share_collapse = 0.0;
  return options;
}

inline Eigen::Vector3d trueStartXYYaw(const sensors::SensorStreams& streams) {
  const Eigen::Isometry3d B_T_M = sensors::trueStartB_T_M(streams);
  return {B_T_M.translation().x(), B_T_M.translation().y(), common::yawOf(B_T_M.linear())};
}

}  // namespace isg::sim::testing
