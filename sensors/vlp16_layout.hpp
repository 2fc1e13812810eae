#pragma once

#include <array>

namespace isg::sensors {

// The Velodyne VLP-16's lasers and timing as its manual gives them (docs/simulation.md): what the
// simulator fires and what the packet decoder reads back. Lasers are numbered in firing order;
// `ring` numbers them by elevation (ring 0 = −15°), as the common Velodyne drivers do.
struct Vlp16Layout {
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
  // The laser (firing order) of a ring: the inverse of ring().
  static constexpr int laser(int ring) { return ring < 8 ? 2 * ring : 2 * (ring - 8) + 1; }
};

}  // namespace isg::sensors
