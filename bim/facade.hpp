#pragma once

#include "bim/plan.hpp"
#include "bim/polygon.hpp"

namespace isg::bim {

// The outline of a level that has no rooms (an open floor: a construction site's slab of columns
// and a façade with gaps, a raster plan whose walls enclose nothing): the convex hull of its
// walls' and columns' footprints, counter-clockwise. Its inside is the level's inside: where the
// robot may start and walk (docs/simulation.md, "Open floors"). Empty for a level without walls.
Polygon2 facadeOutline(const Level& level);

}  // namespace isg::bim
