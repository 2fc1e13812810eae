#pragma once

#include <array>
#include <cstdint>

#include "formats/vlp16_packet.hpp"
#include "formats/vlp16_turns.hpp"

namespace isg::formats {

// What tells one VLP-16 recording from another (docs/sensors.md): the share of shots without an
// echo per ring and overall, the reflectivity's spread, the returns per turn and the span of the
// point times within a turn. The same numbers for a real recording and a simulated one compare
// the simulator with the sensor.
struct Vlp16Statistics {
  std::array<double, 16> lost_by_ring{};  // shots without an echo / shots, by ring (0 = −15°)
  double lost = 0.0;                      // over all rings
  double intensity_median = 0.0;          // over every return
  double intensity_p99 = 0.0;
  double intensity_max = 0.0;
  double points_per_turn = 0.0;  // mean over the complete turns (both echoes in dual mode)
  double turn_duration = 0.0;    // mean span of the point times within a complete turn, s
  int complete_turns = 0;
};

Vlp16Statistics vlp16Statistics(const Vlp16ShotTally& tally, const std::vector<Vlp16Turn>& turns);

}  // namespace isg::formats
