#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <numbers>

#include "sensors/vlp16_layout.hpp"

namespace isg::sim {

// The Velodyne VLP-16's geometry and timing (docs/simulation.md, from the sensor's manual): the
// lasers, elevations and firing times of sensors::Vlp16Layout, which the packet decoder shares, and
// what only the simulator needs. The head spins clockwise seen from above, as the real one does.
struct Vlp16 : sensors::Vlp16Layout {
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
