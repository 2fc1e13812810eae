#pragma once

#include <Eigen/Geometry>
#include <deque>
#include <utility>

#include "sensors/messages.hpp"

namespace isg::slam {

// Where "up" is, from an IMU: Mahony's complementary attitude filter (Mahony, Hamel, Pflimlin,
// "Nonlinear complementary filters on the special orthogonal group", IEEE TAC 2008, the explicit
// filter). The gyroscope is integrated; the estimated up is pulled towards the accelerometer's,
// with a time constant of `time_constant` seconds, only while the accelerometer reads about 1 g:
// the accelerations of walking average out over that time, gravity does not. Roll and pitch are
// therefore absolute; yaw is the gyroscope's integral (M's yaw is the caller's: turnYaw).
// With `estimate_bias`, the filter's integral term estimates the gyroscope's bias (about the
// horizontal axes; the vertical's is not observable from gravity) with the gain that damps the
// tilt's error critically (k_I = k_P² / 4, k_P = 1 / time_constant): without it a bias b holds the
// tilt off by b × time_constant, which a long time constant makes large.
class AttitudeFilter {
 public:
  explicit AttitudeFilter(double time_constant = 2.0, double gravity = 9.81,
                          bool estimate_bias = false)
      : time_constant_(time_constant), gravity_(gravity), estimate_bias_(estimate_bias) {}

  // Samples in time order. The first that reads about 1 g levels the filter at once.
  void add(const sensors::ImuSample& sample);
  bool empty() const { return samples_ == 0; }
  // The orientation of I in M at `t`: interpolated in the last 2 s of history, or moved on from
  // the latest sample at the latest rate.
  Eigen::Matrix3d M_R_I_at(double t) const;
  // Turns the estimate and its history about M's z (a correction of yaw from elsewhere).
  void turnYaw(double angle);
  // Turns M under the estimate and its history: M_q_I becomes turn · M_q_I (a correction of the
  // attitude from elsewhere: the start levelled by the scan's structure).
  void turnFrame(const Eigen::Quaterniond& turn);
  // The estimated gyroscope bias (I, rad/s), when estimated.
  const Eigen::Vector3d& gyroscopeBias() const { return bias_; }

 private:
  double time_constant_, gravity_;
  bool estimate_bias_;
  Eigen::Vector3d bias_ = Eigen::Vector3d::Zero();
  Eigen::Quaterniond M_q_I_ = Eigen::Quaterniond::Identity();
  double time_ = 0.0;
  Eigen::Vector3d last_rate_ = Eigen::Vector3d::Zero();
  int samples_ = 0;
  std::deque<std::pair<double, Eigen::Quaterniond>> history_;  // the last 2 s
};

}  // namespace isg::slam
