#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "bim/plan.hpp"
#include "bim/plan_parser.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"

namespace isg::bim::testing {

// A 6 m × 4 m box with 0.2 m outer walls, split by a 0.1 m wall at x = 3 that meets the outer
// walls in two T-junctions, one door in it and one to the outside. Every number in the geometry
// tests is computed by hand from this plan.
inline nlohmann::json twoRoomPlanJson() {
  return nlohmann::json::parse(R"({
    "format": "isg.plan", "version": 1, "name": "two rooms",
    "levels": [{
      "id": "L0", "elevation": 0.0, "height": 3.0,
      "walls": [
        {"id": "W1", "start": [0, 0], "end": [6, 0], "thickness": 0.2},
        {"id": "W2", "start": [6, 0], "end": [6, 4], "thickness": 0.2},
        {"id": "W3", "start": [6, 4], "end": [0, 4], "thickness": 0.2},
        {"id": "W4", "start": [0, 4], "end": [0, 0], "thickness": 0.2},
        {"id": "W5", "start": [3, 0], "end": [3, 4], "thickness": 0.1, "height": 2.8}
      ],
      "doors": [
        {"id": "D1", "wall": "W5", "offset": 2.0, "width": 0.9, "height": 2.1},
        {"id": "D2", "wall": "W1", "offset": 4.5, "width": 1.0, "height": 2.1, "rooms": ["R2", "outside"]}
      ],
      "rooms": [
        {"id": "R1", "name": "West", "outline": [[0.1, 0.1], [2.95, 0.1], [2.95, 3.9], [0.1, 3.9]]},
        {"id": "R2", "name": "East", "outline": [[3.05, 0.1], [5.9, 0.1], [5.9, 3.9], [3.05, 3.9]]}
      ]
    }]
  })");
}

// A 12 m × 8 m hall of 0.2 m walls with columns: C1 a 0.4 m × 0.3 m rectangle at (3, 2), C2 the
// same turned 90° at (9, 2), C3 a round one 0.4 m across at (3, 6), C4 round, 0.5 m across, at
// (9, 6), 2.5 m tall on a 0.1 m plinth; C5 a round one touching the inner face of the south wall
// (y = 0.1) from (6, 0.25). No rooms: an open floor.
inline nlohmann::json columnHallPlanJson() {
  return nlohmann::json::parse(R"({
    "format": "isg.plan", "version": 1, "name": "column hall",
    "levels": [{
      "id": "L0", "height": 3.0,
      "walls": [
        {"id": "W1", "start": [0, 0], "end": [12, 0], "thickness": 0.2},
        {"id": "W2", "start": [12, 0], "end": [12, 8], "thickness": 0.2},
        {"id": "W3", "start": [12, 8], "end": [0, 8], "thickness": 0.2},
        {"id": "W4", "start": [0, 8], "end": [0, 0], "thickness": 0.2}
      ],
      "columns": [
        {"id": "C1", "center": [3, 2], "size": [0.4, 0.3]},
        {"id": "C2", "center": [9, 2], "size": [0.4, 0.3], "yaw": 1.5707963267948966},
        {"id": "C3", "center": [3, 6], "diameter": 0.4},
        {"id": "C4", "center": [9, 6], "diameter": 0.5, "height": 2.6, "base": 0.1, "name": "tube"},
        {"id": "C5", "center": [6, 0.25], "diameter": 0.4}
      ]
    }]
  })");
}

inline Plan parsePlanJson(const nlohmann::json& document, common::Warnings* warnings = nullptr,
                          const std::string& file = "test.json") {
  const common::JsonSource source{file, warnings};
  return parsePlan(common::JsonNode(document, "", source));
}

// The message a plan is refused with, or "(accepted)".
inline std::string planErrorOf(const nlohmann::json& document) {
  try {
    parsePlanJson(document);
  } catch (const common::InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

}  // namespace isg::bim::testing
