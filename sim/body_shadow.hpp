#pragma once

#include <Eigen/Geometry>

#include "sim/robot_model.hpp"

namespace isg::sim {

// Where a ray of the sensor meets the robot's own body. The body is rigid with the mount, so for a
// given laser and azimuth the answer is the same in every turn: the simulator asks once per
// firing. The body is the box of robotBodyBox(); the legs stand under it (hips and knees within
// its footprint), in its shadow from a sensor on top.
class BodyShadow {
 public:
  BodyShadow(const RobotBox& body, const Eigen::Isometry3d& R_T_L);

  // Distance along the ray (origin and unit direction in the sensor frame L) to the body, or a
  // negative number when the ray misses it.
  double distance(const Eigen::Vector3d& origin_L, const Eigen::Vector3d& direction_L) const;

 private:
  RobotBox body_;
  Eigen::Isometry3d R_T_L_;
};

}  // namespace isg::sim
