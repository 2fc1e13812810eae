#pragma once

#include <utility>
#include <vector>

#include "bim/agraph.hpp"
#include "run/run_metrics.hpp"
#include "run/run_record.hpp"

namespace isg::run {

// The floor (index into graph.floors) a robot whose base is at height z in B stands on: the one
// with the highest elevation at or below z (the lowest when z is below all); -1 without floors.
// On a flight that is the level it climbs from until its base passes the next level's floor.
int floorAt(const bim::AGraph& graph, double z);

// metrics.json `levels` (run/run_metrics.hpp): for each level the ground truth stood on, in the
// order first reached, its time there, the first estimate (in B) that put the robot on it while
// it was there, and the APE in B rows (t, error) taken while there. Empty for a plan of one level.
std::vector<LevelMetrics> levelMetrics(const bim::AGraph& graph, common::PoseSequence ground_truth,
                                       const Trajectory& estimate,
                                       const std::vector<std::pair<double, double>>& ape_rows);

}  // namespace isg::run
