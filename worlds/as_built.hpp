#pragma once

#include "bim/plan.hpp"
#include "bim/scenario.hpp"

namespace isg::worlds {

// The level as it was built: the plan's walls with a scenario's deviations applied. Missing walls
// are gone (with their doors), turned and shifted walls stand where bim::builtWall puts them (their
// doors and windows, placed along the wall from its start, go with them), extra walls added with
// their generated ids. A wall built in part (`shortened_walls`) is replaced by the parts that
// stand, ids `ID#1`, `ID#2`, …, with the doors and windows in them. Doors listed as closed stay
// openings here; the world generator fills them with a door leaf. Clutter is not a wall and is not
// included.
bim::Level asBuiltLevel(const bim::Level& level, const bim::AsBuilt& as_built);

}  // namespace isg::worlds
