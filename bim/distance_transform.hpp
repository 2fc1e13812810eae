#pragma once

#include <vector>

namespace isg::bim {

// Exact squared Euclidean distance transform of a grid (Felzenszwalb & Huttenlocher, 2012): for
// every cell, the squared distance in cells, centre to centre, to the nearest cell marked in
// `source` (row-major, width × height). With no source cell at all every distance is huge
// (1e12): callers cap it.
std::vector<double> squaredDistanceTransform(const std::vector<char>& source, int width,
                                             int height);

}  // namespace isg::bim
