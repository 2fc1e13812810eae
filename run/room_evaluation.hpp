#pragma once

#include <string>
#include <vector>

#include "bim/plan.hpp"
#include "eval/alignment.hpp"
#include "sensors/sensor_streams.hpp"
#include "slam/map_diagnostics.hpp"

namespace isg::run {

// How well a map found the rooms (docs/slam.md, "Rooms"): of the plan's four-wall rooms and
// corridors the robot walked through (a ground-truth pose inside the outline), those matched by a
// confirmed map room whose centre, taken into B by `B_from_M`, lies inside the plan room and
// whose widths are within `tolerance` of the A-Graph room's (sorted; a corridor's one width
// against the room's narrower one).
struct RoomDetectionReport {
  std::vector<std::string> walked;    // plan room ids
  std::vector<std::string> detected;  // of those
  double worst_width_error = 0.0;     // over the detected ones, metres
  double rate() const { return walked.empty() ? 1.0 : double(detected.size()) / walked.size(); }
};

RoomDetectionReport evaluateRooms(const bim::Plan& plan, const std::string& level,
                                  const std::vector<slam::MapRoom>& rooms,
                                  common::PoseSequence ground_truth,
                                  const eval::Similarity& B_from_M, double tolerance = 0.1);

}  // namespace isg::run
