#pragma once

#include "worlds/plan_generator.hpp"

namespace isg::worlds {

// The "site" family (docs/sweeps.md, "Construction sites"): one open-plan floor of a building
// under construction, as a site's plan has it and as the site stands. A rectangular slab (one
// corner cut on a slant in most) on a grid of columns 6–8 m apart; a façade of columns with bays
// closed by walls with windows or still open; an off-centre core of small rooms (shafts, toilets,
// a stair) opening onto the floor through doorways; a few free-standing partitions, one at an
// angle. The plan has no rooms: the floor's inside is its façade (docs/simulation.md, "Open
// floors"). As built: some façade walls and a partition not built yet, and pallets of material
// on the floor. The robot tours the open floor. Columns are written as walls of their footprint
// named "column" (ids C1, C2 …), as the raster import writes them.
GeneratedBuilding generateSite(const GeneratorSpec& spec);

}  // namespace isg::worlds
