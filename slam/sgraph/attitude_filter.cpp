#include "slam/sgraph/attitude_filter.hpp"

#include <algorithm>

namespace isg::slam {

void AttitudeFilter::add(const sensors::ImuSample& sample) {
  const Eigen::Vector3d& a = sample.accelerometer;
  const double g = a.norm();
  // The accelerometer tells gravity only while it reads about 1 g.
  const bool tells_gravity = g > 0.5 * gravity_ && g < 1.5 * gravity_;
  if (samples_ == 0) {
    // Level at the first sample: I's up as measured becomes M's z.
    if (tells_gravity) M_q_I_ = Eigen::Quaterniond::FromTwoVectors(a / g, Eigen::Vector3d::UnitZ());
  } else {
    const double dt = sample.t - time_;
    if (!(dt > 0.0) || dt > 1.0) {
      time_ = sample.t;
      return;
    }
    // The rate, plus a pull of the estimated up (in I) towards the measured one.
    Eigen::Vector3d rate = sample.gyroscope - bias_;
    if (tells_gravity) {
      const Eigen::Vector3d up_estimated = M_q_I_.conjugate() * Eigen::Vector3d::UnitZ();
      const Eigen::Vector3d error = (a / g).cross(up_estimated);
      rate += error / time_constant_;
      if (estimate_bias_) bias_ -= error * (dt / (4.0 * time_constant_ * time_constant_));
    }
    const Eigen::Vector3d turn = rate * dt;
    if (turn.norm() > 0.0) {
      M_q_I_ = M_q_I_ * Eigen::Quaterniond(Eigen::AngleAxisd(turn.norm(), turn.normalized()));
      M_q_I_.normalize();
    }
  }
  last_rate_ = sample.gyroscope - bias_;
  time_ = sample.t;
  ++samples_;
  history_.push_back({sample.t, M_q_I_});
  while (history_.size() > 2 && history_.front().first < sample.t - 2.0) history_.pop_front();
}

Eigen::Matrix3d AttitudeFilter::M_R_I_at(double t) const {
  if (history_.empty()) return Eigen::Matrix3d::Identity();
  if (t >= history_.back().first) {
    const Eigen::Vector3d turn = last_rate_ * (t - history_.back().first);
    Eigen::Quaterniond q = history_.back().second;
    if (turn.norm() > 0.0)
      q = q * Eigen::Quaterniond(Eigen::AngleAxisd(turn.norm(), turn.normalized()));
    return q.toRotationMatrix();
  }
  if (t <= history_.front().first) return history_.front().second.toRotationMatrix();
  const auto hi = std::lower_bound(
      history_.begin(), history_.end(), t,
      [](const std::pair<double, Eigen::Quaterniond>& h, double time) { return h.first < time; });
  const auto lo = hi - 1;
  const double s = (t - lo->first) / (hi->first - lo->first);
  return lo->second.slerp(s, hi->second).toRotationMatrix();
}

void AttitudeFilter::turnYaw(double angle) {
  turnFrame(Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ())));
}

void AttitudeFilter::turnFrame(const Eigen::Quaterniond& turn) {
  M_q_I_ = (turn * M_q_I_).normalized();
  for (auto& [time, q] : history_) q = (turn * q).normalized();
}

}  // namespace isg::slam
