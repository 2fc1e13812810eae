#pragma once

#include <vector>

#include "bim/plan.hpp"
#include "bim/polygon.hpp"

namespace isg::bim {

// Rooms where a plan has walls but no rooms (an IFC storey without IfcSpace; a raster floor plan):
// the free regions the walls enclose. The walls' footprints (with their joint extensions, door
// openings closed: a door separates two rooms) are drawn on a grid; the free space connected to
// the grid's border is outside; every other connected free region of at least `min_area` is a
// room, its outline the region's outer boundary (holes such as columns left out), traced along
// the cells' edges and straightened within one cell.
struct FreeSpaceOptions {
  double cell = 0.05;     // m; coarsened so that the grid holds at most max_cells
  double min_area = 1.0;  // m²: smaller enclosed pockets (shafts drawn solid, gaps) are no rooms
  long max_cells = 40'000'000;
};

struct FreeSpaceRooms {
  std::vector<Polygon2> outlines;  // counter-clockwise, simple, in the order found (by x, then y)
  int pockets = 0;                 // enclosed regions smaller than min_area, left out
  double cell = 0.0;               // the cell size used
};

FreeSpaceRooms enclosedFreeSpaces(const Level& level, const FreeSpaceOptions& options = {});

}  // namespace isg::bim
