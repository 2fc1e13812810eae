#pragma once

#include <Eigen/Geometry>
#include <array>

namespace isg::sensors {

// A sensor mount [x, y, z, roll, pitch, yaw] on the base R as the transform R_T_sensor: the
// rotation is R_z(yaw) · R_y(pitch) · R_x(roll), as docs/formats.md writes the mounts.
Eigen::Isometry3d mountTransform(const std::array<double, 6>& xyz_rpy);

// The inverse: [x, y, z, roll, pitch, yaw] of a rigid transform, pitch within ±90° (at ±90°,
// roll 0 and the turn about z all in yaw).
std::array<double, 6> mountXyzRpy(const Eigen::Isometry3d& R_T_sensor);

}  // namespace isg::sensors
