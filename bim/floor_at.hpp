#pragma once

#include "bim/agraph.hpp"

namespace isg::bim {

// The floor (index into graph.floors) a robot whose base is at height z in B stands on: the one
// with the highest elevation at or below z (the lowest when z is below all); -1 without floors.
// On a flight that is the level it climbs from until its base passes the next level's floor.
int floorAt(const AGraph& graph, double z);

}  // namespace isg::bim
