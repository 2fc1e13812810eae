#pragma once

#include "slam/map_diagnostics.hpp"

namespace isg::slam {

// Whether the map could only have seen `wall` through another of its walls: from every keyframe
// that saw it, the sight line (in M, from the keyframe's optimised sensor position) to each of
// its ends and its middle crosses another map wall seen from at least `min_occluder_observations`
// keyframes, standing over the wall's heights, at a part the map confirms built (at least
// `margin` inside it: a sight line through a door or past an end is not blocked), more than
// `margin` in front of the wall. A plane fitted once from a scan skewed in a fast turn lies so,
// behind the face it was fitted to. False when no keyframe that saw it is known.
bool seenOnlyThroughWalls(const MapDiagnostics& map, const MapWall& wall,
                          int min_occluder_observations, double margin);

}  // namespace isg::slam
