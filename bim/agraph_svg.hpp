#pragma once

#include <string>

#include "bim/agraph.hpp"
#include "bim/plan.hpp"

namespace isg::bim {

// An SVG picture of one level of the plan with its A-Graph drawn over it: wall footprints,
// wall surfaces (x-surfaces red, y-surfaces blue), wall centres, rooms with their centres and
// kinds, doorway nodes with their edges to the rooms they join, and the floor node.
std::string agraphToSvg(const Plan& plan, const AGraph& graph, const std::string& level_id);

}  // namespace isg::bim
