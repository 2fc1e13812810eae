#pragma once

#include "worlds/plan_generator.hpp"

namespace isg::worlds {

// The "parking" family (docs/sweeps.md, "Car parks"): one underground floor of a car park, as
// its plan has it and as it stands while the building goes up. A rectangular slab of 6–9 × 4–6
// bays of 7.5–8.5 m on a grid of identical columns (square on some floors, round on others); a
// perimeter of retaining walls from column to column, open only at the ramp's foot; the ramp's
// two walls reaching 1.3–1.8 bays into the floor; a stair core and a lift core, each a lobby
// opening onto the floor and a stair or a shaft behind it. The plan has no rooms: the floor's
// inside is its perimeter (docs/simulation.md, "Open floors"). As built: one to three perimeter
// walls not built yet, on most a bay built beyond one of them that the plan does not show (the
// tour walks into it), vehicles parked between the columns and pallets of material. The robot
// tours the open floor; `spec.carrier` says whether it is legged or carried by hand.
GeneratedBuilding generateParking(const GeneratorSpec& spec);

}  // namespace isg::worlds
