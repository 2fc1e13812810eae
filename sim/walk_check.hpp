#pragma once

#include "bim/scenario.hpp"

namespace isg::sim {

// A replayed walk must not pass through what stands on the robot's level as built: a point of the
// walk (its poses and the straight steps between them) inside a wall's or column's solid (its
// doorways are open) or a clutter box, by more than worlds::kWalkSolidTolerance, is an InputError
// naming the walk's file and the pose's line (docs/simulation.md, "Replayed walks"). What remains
// here is what the scenario put there: the planned walls and columns a walk crosses are taken as
// not built (or opened) when the scenario is read (worlds::takeCrossedSolids), unless its route
// says "crossed": "refuse".
void checkWalkClear(const bim::Scenario& scenario);

}  // namespace isg::sim
