#pragma once

namespace isg::sim {

// Distance, speed and acceleration at one instant of a movement along a line or about an axis.
struct MotionState {
  double distance = 0.0;
  double rate = 0.0;
  double acceleration = 0.0;
};

// A rest-to-rest movement over `distance` (metres or radians) at most `rate` per second and at
// most `acceleration` per second squared: the speed rises from zero along a raised cosine, holds,
// and falls the same way. Speed and acceleration are continuous (the acceleration is zero at both
// ends), so the motion can be differentiated twice, as an accelerometer needs. A movement too
// short to reach `rate` peaks lower, with the same ramp time.
class RestToRestProfile {
 public:
  RestToRestProfile(double distance, double rate, double acceleration);

  double duration() const { return 2.0 * ramp_ + cruise_; }
  double peakRate() const { return peak_; }
  // At `tau` seconds after the start, clamped to [0, duration()].
  MotionState at(double tau) const;

 private:
  MotionState ramp(double tau) const;  // the first ramp, tau in [0, ramp_]

  double distance_;
  double ramp_ = 0.0;    // seconds of each ramp
  double cruise_ = 0.0;  // seconds at the peak rate
  double peak_ = 0.0;
};

}  // namespace isg::sim
