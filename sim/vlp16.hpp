#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <numbers>

namespace isg::sim {

// The Velodyne VLP-16's geometry and timing (docs/simulation.md, from the sensor's manual).
// Lasers are numbered in firing order; `ring` numbers them by elevation (ring 0 = −15°), as the
// common Velodyne drivers do. The head spins clockwise seen from above, as the real one does.
struct Vlp16 {
  static constexpr int kLasers = 16;
  static constexpr double kFiringInterval = 2.304e-6;     // s between two lasers of a sequence
  static constexpr double kSequenceDuration = 55.296e-6;  // s per firing sequence
  static constexpr std::array<double, kLasers> kElevationDeg = {-15, 1, -13, 3,  -11, 5,  -9, 7,
                                                                -7,  9, -5,  11, -3,  13, -1, 15};
  // Each laser's origin sits this far above (+) or below the optical centre.
  static constexpr std::array<double, kLasers> kVerticalOffsetMm = {
      11.2, -0.7, 9.7, -2.2, 8.1, -3.7, 6.6, -5.1, 5.1, -6.6, 3.7, -8.1, 2.2, -9.7, 0.7, -11.2};

  static constexpr int ring(int laser) {
    return laser % 2 == 0 ? laser / 2 : 8 + laser / 2;  // -15,-13,...,-1 then 1,3,...,15
  }

  // Firing sequences in one turn at `rate_hz` (1808 at 10 Hz: a 0.199° azimuth step).
  static int sequencesPerTurn(double rate_hz) {
    return int(std::floor(1.0 / (rate_hz * kSequenceDuration)));
  }

  // Time of a laser's firing from the start of the turn.
  static constexpr double firingTime(int sequence, int laser) {
    return kSequenceDuration * sequence + kFiringInterval * laser;
  }

  // The head's angle at time t into a turn: clockwise, so the azimuth (counter-clockwise from
  // the sensor's x axis) decreases from 0.
  static double azimuth(double t, double rate_hz) { return -2.0 * std::numbers::pi * rate_hz * t; }

  // Unit direction of a laser in the sensor frame L at a given azimuth.
  static Eigen::Vector3d direction(int laser, double azimuth) {
    const double el = kElevationDeg[laser] * std::numbers::pi / 180.0;
    return {std::cos(el) * std::cos(azimuth), std::cos(el) * std::sin(azimuth), std::sin(el)};
  }

  static Eigen::Vector3d origin(int laser) { return {0.0, 0.0, kVerticalOffsetMm[laser] * 1e-3}; }
};

}  // namespace isg::sim
