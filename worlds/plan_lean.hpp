#pragma once

#include <nlohmann/json.hpp>

#include "bim/scenario.hpp"

namespace isg::worlds {

// A generated building made non-Manhattan (docs/sweeps.md, "Non-Manhattan buildings"): sheared by
// `shear_deg` along x, so that the walls that ran along y lean that far from square and every
// room becomes a parallelogram, then turned by `turn_deg` about B's origin. The plan's walls,
// rooms, doors and the as-built changes move with it:
// - points (wall ends, room corners, extra walls, clutter centres) are mapped;
// - what is measured along a wall (door offsets and widths, a turn's pivot in metres, the parts
//   of a wall built in part) is stretched as the wall is, so it stays on the same stretch of wall;
// - wall thickness is across the wall: divided by the same stretch (the shear keeps areas), so
//   that the faces stay on the room outlines;
// - a wall shift stays what it is, metres along the wall's own normal; a turn stays its angle;
// - clutter boxes keep their shape and turn with the building; a box the shear would push into
//   a wall (within 0.05 m of its faces) is left out.
// Shear 0 and turn 0 leave the building as it was, byte for byte. `plan` is an "isg.plan" and
// `as_built` what its scenario says was built otherwise.
void leanBuilding(nlohmann::json& plan, bim::AsBuilt& as_built, double shear_deg, double turn_deg);

}  // namespace isg::worlds
