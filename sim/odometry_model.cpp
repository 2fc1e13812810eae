#include "sim/odometry_model.hpp"

#include <cmath>
#include <numbers>

#include "common/angles.hpp"

namespace isg::sim {

OdometryModel::OdometryModel(const bim::OdometryConfig& config,
                             const Eigen::Isometry3d& B_T_R_start)
    : config_(config), previous_(B_T_R_start), start_(B_T_R_start) {}

Eigen::Isometry3d OdometryModel::update(const Eigen::Isometry3d& B_T_R, std::mt19937_64& rng) {
  // The true planar increment, in the previous base frame.
  const double yaw0 = common::yawOf(previous_.linear());
  const double yaw1 = common::yawOf(B_T_R.linear());
  const Eigen::Vector2d world_step = (B_T_R.translation() - previous_.translation()).head<2>();
  const Eigen::Vector2d step = Eigen::Rotation2Dd(-yaw0) * world_step;
  const double turn = common::wrapAngle(yaw1 - yaw0);
  const double distance = step.norm();
  previous_ = B_T_R;

  std::normal_distribution<double> n(0.0, 1.0);
  const double sigma_xy = config_.translation_noise * std::sqrt(distance);
  const double heading_var =
      std::pow(config_.heading_noise_deg_per_m * std::numbers::pi / 180.0, 2) * distance +
      kRotationNoise * kRotationNoise * std::abs(turn);
  const double dx = step.x() + sigma_xy * n(rng);
  const double dy = step.y() + sigma_xy * n(rng);
  const double dyaw = turn + std::sqrt(heading_var) * n(rng) +
                      config_.heading_bias_deg_per_m * std::numbers::pi / 180.0 * distance;
  const Eigen::Vector2d moved = Eigen::Rotation2Dd(planar_.z()) * Eigen::Vector2d(dx, dy);
  planar_.x() += moved.x();
  planar_.y() += moved.y();
  planar_.z() = common::wrapAngle(planar_.z() + dyaw);

  // Height, roll and pitch relative to the start, from the truth (less what kidnaps carried).
  const Eigen::Matrix3d tilt =
      Eigen::AngleAxisd(-yaw1, Eigen::Vector3d::UnitZ()).toRotationMatrix() * B_T_R.linear();
  Eigen::Isometry3d M_T_R = Eigen::Isometry3d::Identity();
  M_T_R.translation() = Eigen::Vector3d(
      planar_.x(), planar_.y(), B_T_R.translation().z() - start_.translation().z() + lifted_);
  M_T_R.linear() =
      Eigen::AngleAxisd(planar_.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix() * tilt;
  return M_T_R;
}

}  // namespace isg::sim
