#include "sim/motion_profile.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace isg::sim {

using std::numbers::pi;

RestToRestProfile::RestToRestProfile(double distance, double rate, double acceleration)
    : distance_(std::max(0.0, distance)) {
  if (distance_ == 0.0) return;
  // A raised-cosine ramp to speed v over T reaches its largest acceleration, v·π/(2T), halfway.
  ramp_ = pi * rate / (2.0 * acceleration);
  // Two ramps cover v·T together: a shorter movement keeps T and peaks lower.
  peak_ = std::min(rate, distance_ / ramp_);
  cruise_ = std::max(0.0, distance_ / peak_ - ramp_);
}

MotionState RestToRestProfile::ramp(double tau) const {
  const double w = pi / ramp_;
  return {peak_ * (0.5 * tau - std::sin(w * tau) / (2.0 * w)),
          peak_ * 0.5 * (1.0 - std::cos(w * tau)), peak_ * 0.5 * w * std::sin(w * tau)};
}

MotionState RestToRestProfile::at(double tau) const {
  if (distance_ == 0.0) return {};
  tau = std::clamp(tau, 0.0, duration());
  if (tau <= ramp_) return ramp(tau);
  if (tau <= ramp_ + cruise_) return {peak_ * (0.5 * ramp_ + (tau - ramp_)), peak_, 0.0};
  // The second ramp mirrors the first in time.
  const MotionState mirrored = ramp(duration() - tau);
  return {distance_ - mirrored.distance, mirrored.rate, -mirrored.acceleration};
}

}  // namespace isg::sim
