#pragma once

#include <nlohmann/json.hpp>

#include "slam/isgraph/compiled_plan.hpp"
#include "slam/isgraph/floor_following.hpp"
#include "slam/isgraph/held_answer.hpp"
#include "slam/isgraph/match_log.hpp"
#include "slam/isgraph/released_walls.hpp"

namespace isg::slam {

// The parts of the iS-Graph a run folder's sgraph.json shows under "matching" (docs/evaluation.md):
// the status and its log, the answer held (B_T_M, the level, the correspondences by plan id), the
// walls released, the levels reached.
struct ISGraphView {
  const CompiledPlan& plan;
  const HeldAnswer& answer;
  const MatchLog& log;
  const ReleasedWalls& released;
  const FloorFollower& floors;
  int windows_with_answer_held = 0;
  long jamb_factors = 0;  // door jambs tied to keyframes, over every window
  int map_bends = 0;      // whole-map optimisations with the plan (bend_keyframes)
};

// sgraph.json's "matching" object of the iS-Graph.
nlohmann::json matchingJson(const ISGraphView& view);

}  // namespace isg::slam
