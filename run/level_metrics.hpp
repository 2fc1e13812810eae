#pragma once

#include <utility>
#include <vector>

#include "bim/agraph.hpp"
#include "run/run_metrics.hpp"
#include "run/run_record.hpp"

namespace isg::run {

// metrics.json `levels` (run/run_metrics.hpp): for each level the ground truth stood on, in the
// order first reached, its time there, the first estimate (in B) that put the robot on it while
// it was there, and the APE in B rows (t, error) taken while there. Empty for a plan of one level.
std::vector<LevelMetrics> levelMetrics(const bim::AGraph& graph, common::PoseSequence ground_truth,
                                       const Trajectory& estimate,
                                       const std::vector<std::pair<double, double>>& ape_rows);

}  // namespace isg::run
