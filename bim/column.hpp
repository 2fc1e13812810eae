#pragma once

#include <Eigen/Core>
#include <vector>

#include "bim/plan.hpp"

namespace isg::bim {

// A rectangular column as the wall it is geometrically: its axis along the column's width
// through its centre, its thickness the column's depth, its id, name, height and base. The
// level's geometry (computeLevelGeometry) takes rectangular columns this way, so that their faces
// are wall faces for the A-Graph, the world, the route grid and the pictures alike.
Wall columnWall(const Column& column);

// The column's outline, counter-clockwise: a rectangle's four corners, or for a round column the
// regular polygon of `sides` sides whose edges touch the circle from outside (it covers the
// column: a grid painted from it never lets a path graze the column).
std::vector<Eigen::Vector2d> columnFootprint(const Column& column, int sides = 24);

}  // namespace isg::bim
