#pragma once

#include "bim/plan.hpp"
#include "bim/polygon.hpp"

namespace isg::bim {

// The outline of a level that has no rooms (an open floor: a construction site's slab of columns
// and a façade with gaps, a raster plan whose walls enclose nothing): the convex hull of its
// walls' and columns' footprints, counter-clockwise. Its inside is the level's inside: where the
// robot may start and walk (docs/simulation.md, "Open floors"). Empty for a level without walls.
Polygon2 facadeOutline(const Level& level);

// Whether a level is an open floor: it has no rooms, or its rooms cover under kOpenFloorRoomShare
// of its façade's outline (a construction site's slab whose core of shafts and toilets is all
// that is enclosed, a raster site plan in which only the core's rooms close). Its inside is then
// the façade's, its tour the open floor's lattice and then its rooms (docs/simulation.md, "Open
// floors"). Every roomed building measured covers at least 0.44 of its outline with rooms (D1–D6
// 0.83–0.91, the hall world 0.44, L-shaped generated floors 0.66, the IFC test models 0.70–0.92).
inline constexpr double kOpenFloorRoomShare = 0.25;
bool isOpenFloor(const Level& level);

}  // namespace isg::bim
