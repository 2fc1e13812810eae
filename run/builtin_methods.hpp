#pragma once

#include "run/localizer_registry.hpp"

namespace isg::run {

// The testbed's methods, each added by its own file (run/method_*.cpp):
// - is-graphs: the S-Graph matched to and merged with the plan's A-Graph (global localization);
// - s-graph: the S-Graph alone, SLAM in its own frame M, never localized in the plan;
// - amcl: ROS AMCL's 2D Monte Carlo localization in the plan's occupancy grid, global start;
// - ndt-ukf: hdl_localization's NDT scan matching with an unscented Kalman filter, a tracker
//   given its start pose perturbed;
// - odometry (alias dead-reckoning): odometry with M placed at the true start pose (a baseline
//   that is given the start).
// docs/baselines.md describes the baselines.
void addISGraphs(LocalizerRegistry& registry);
void addAmcl(LocalizerRegistry& registry);
void addNdtUkf(LocalizerRegistry& registry);
void addSGraph(LocalizerRegistry& registry);
void addDeadReckoning(LocalizerRegistry& registry);

// A registry with all of them, in that order.
LocalizerRegistry builtinMethods();

}  // namespace isg::run
