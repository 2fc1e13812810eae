#pragma once

#include "slam/isgraph/graph_matching.hpp"
#include "slam/sgraph/sgraph.hpp"

namespace isg::slam {

// The S-Graph as the matcher sees it (walls of a minimum height, confirmed rooms, transitions),
// of the floor the robot stands on (the latest one it stood on, while on the stairs).
MatchInput matchInputOf(const SGraph& graph, double min_wall_height);

}  // namespace isg::slam
