#pragma once

#include <vector>

#include "formats/vlp16_packet.hpp"

namespace isg::formats {

// One turn of the head: the returns from one crossing of the cut azimuth to the next.
struct Vlp16Turn {
  std::vector<Vlp16Point> points;
  bool complete = false;  // false for the recording's first and last turns: they are cut short
};

// Cuts decoded returns (in firing order) into turns at `cut_deg` (0.01° resolution, the packet's
// unit): a point belongs to the turn its azimuth has reached since the last crossing, unwrapped
// along the firing order, so the two echoes of a shot always fall in the same turn and a
// recording that starts anywhere cuts the same way.
std::vector<Vlp16Turn> cutIntoTurns(const std::vector<Vlp16Point>& points, double cut_deg = 0.0);

}  // namespace isg::formats
