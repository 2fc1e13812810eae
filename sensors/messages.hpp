#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace isg::sensors {

// What the localizer consumes: plain sensor data, the same from the simulator or a real robot.

// One LiDAR return, in the LiDAR frame L at its own firing instant (not deskewed).
struct ScanPoint {
  float x, y, z;
  float intensity;
  std::uint16_t ring;  // laser index by elevation (0 = lowest)
  float time;          // seconds after the scan's stamp
};

// One turn of the LiDAR.
struct Scan {
  double stamp = 0.0;  // time of the turn's first firing
  std::vector<ScanPoint> points;
};

// The base's pose in the odometry frame M (the start pose) at a time.
struct Odometry {
  double stamp = 0.0;
  Eigen::Isometry3d M_T_R = Eigen::Isometry3d::Identity();
};

// One reading of an IMU, in its own frame I: specific force (m/s², gravity included: a unit at
// rest reads +g upwards) and angular velocity (rad/s).
struct ImuSample {
  double t = 0.0;
  Eigen::Vector3d accelerometer = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyroscope = Eigen::Vector3d::Zero();
};

}  // namespace isg::sensors
