#pragma once

#include "bim/scenario.hpp"

namespace isg::sim {

// A replayed walk must not pass through what stands on the robot's level as built: a pose whose
// position lies inside a wall's or column's solid (its doorways are open) or a clutter box, by
// more than kWalkSolidTolerance, is an InputError naming the walk's file and the pose's line
// (docs/formats.md, "Replayed walks"). Walls whose base is above the carrier's height do not
// count. Near walls is allowed: a walker passes closer than a planned route's clearance.
inline constexpr double kWalkSolidTolerance = 0.02;  // m

void checkWalkClear(const bim::Scenario& scenario);

}  // namespace isg::sim
