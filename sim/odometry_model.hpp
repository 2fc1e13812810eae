#pragma once

#include <Eigen/Geometry>
#include <random>

#include "bim/scenario.hpp"

namespace isg::sim {

// Legged odometry (docs/simulation.md): the true motion between two ticks, with noise that grows
// with distance and rotation, integrated in the map frame M (the start pose, which the localizer
// does not know in B).
//
// The noise is a random walk, so it does not depend on the odometry rate: over 1 m of travel the
// position error has standard deviation `translation_noise` · 1 m and the heading error
// `heading_noise_deg_per_m` degrees, growing with the square root of the distance; turning adds
// heading noise of 1 % of √(rotation · 1 rad). `heading_bias_deg_per_m` adds a systematic drift.
// Height, roll and pitch come from the true pose (the IMU and leg kinematics observe them well).
class OdometryModel {
 public:
  OdometryModel(const bim::OdometryConfig& config, const Eigen::Isometry3d& B_T_R_start);

  // The estimate M_T_R after moving to the true pose B_T_R.
  Eigen::Isometry3d update(const Eigen::Isometry3d& B_T_R, std::mt19937_64& rng);
  // The robot was carried to B_T_R (a kidnap): the legs did not move, so odometry does not see it.
  // Nor its height: carried to another floor, the odometry's height stays where it was.
  void teleport(const Eigen::Isometry3d& B_T_R) {
    lifted_ += previous_.translation().z() - B_T_R.translation().z();
    previous_ = B_T_R;
  }

  static constexpr double kRotationNoise = 0.01;  // rad per √rad

 private:
  bim::OdometryConfig config_;
  Eigen::Isometry3d previous_;
  Eigen::Isometry3d start_;
  Eigen::Vector3d planar_ = Eigen::Vector3d::Zero();  // x, y, yaw in M
  double lifted_ = 0.0;  // the height the kidnaps carried the robot, which M does not see
};

}  // namespace isg::sim
