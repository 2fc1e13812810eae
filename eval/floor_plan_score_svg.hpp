#pragma once

#include <string>
#include <vector>

#include "eval/floor_plan_score.hpp"

namespace isg::eval {

// The picture of a floor-plan score (isg eval --floor-plan-score --plot): a title, `summary`
// lines, each associated pose's score over time (0 … 100) and its error in metres; the moment
// scoring starts is the dashed line.
std::string floorPlanScoreSvg(const FloorPlanScore& score, const std::string& title,
                              const std::vector<std::string>& summary);

}  // namespace isg::eval
