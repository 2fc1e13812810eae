#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <string>

#include "sim/base_motion.hpp"

namespace isg::sim {

// A Spot-like quadruped for the world: body 1.1 × 0.5 m, hips at x ±0.30, y ±0.055 m, two hinge
// joints per leg (hip and knee), standing 0.46 m high, with the VLP-16 puck on its mount. It is a
// mocap body moved by the scripted trajectory, its legs set by the trot; its geoms are in
// worlds::kRobotGroup, which the simulated LiDAR never sees, and collide with nothing.
std::string robotMjcf(const Eigen::Isometry3d& R_T_L);

// Puts the robot at B_T_R with its legs at the gait's phase, and updates the kinematics (only the
// latter in a world without the robot).
void poseRobot(const mjModel& model, mjData& data, const Eigen::Isometry3d& B_T_R,
               double gait_phase, double sway_weight);

// The robot's body as a box in its base frame R (for tests: no LiDAR point may fall inside it).
struct RobotBox {
  Eigen::Vector3d centre;
  Eigen::Vector3d half;
};
RobotBox robotBodyBox();

}  // namespace isg::sim
