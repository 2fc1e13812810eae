#pragma once

#include <random>

#include "slam/baselines/pose2.hpp"

namespace isg::slam {

// The odometry motion model of Probabilistic Robotics (Thrun, Burgard, Fox, table 5.6), as ROS
// AMCL's differential model implements it: a move between two odometry poses is a turn (rot1),
// a straight run (trans) and a turn (rot2), each disturbed by zero-mean noise whose standard
// deviation grows with the motion. nav2's defaults: every alpha 0.2.
struct OdometryMotionNoise {
  double alpha1 = 0.2;  // rotation noise from rotation
  double alpha2 = 0.2;  // rotation noise from translation
  double alpha3 = 0.2;  // translation noise from translation
  double alpha4 = 0.2;  // translation noise from rotation
};

struct OdometryMotion {
  double rot1 = 0.0;
  double trans = 0.0;
  double rot2 = 0.0;
  // The turns' sizes for the noise: a move backwards is a small turn and a run, not two half
  // turns (AMCL takes the smaller of |rot| and |π − rot|).
  double rot1_noise = 0.0;
  double rot2_noise = 0.0;
  // Standard deviations of the three noises.
  double sigmaRot1(const OdometryMotionNoise& n) const;
  double sigmaTrans(const OdometryMotionNoise& n) const;
  double sigmaRot2(const OdometryMotionNoise& n) const;
};

// The move from odometry pose `from` to `to`. Below 1 cm of travel rot1 is 0 (AMCL's rule: the
// direction of a tiny move is noise).
OdometryMotion decomposeOdometry(const Pose2& from, const Pose2& to);

// A particle's pose after the move, drawn from the model.
Pose2 sampleOdometryMotion(const Pose2& particle, const OdometryMotion& motion,
                           const OdometryMotionNoise& noise, std::mt19937_64& rng);

}  // namespace isg::slam
