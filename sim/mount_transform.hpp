#pragma once

#include <Eigen/Geometry>
#include <array>

namespace isg::sim {

// A sensor mount [x, y, z, roll, pitch, yaw] on the base R as the transform R_T_sensor: the
// rotation is R_z(yaw) · R_y(pitch) · R_x(roll), as docs/formats.md
// writes the mounts.
Eigen::Isometry3d mountTransform(const std::array<double, 6>& xyz_rpy);

}  // namespace isg::sim
