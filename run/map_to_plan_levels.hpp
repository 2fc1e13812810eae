#pragma once

#include <vector>

#include "run/run_metrics.hpp"
#include "run/run_record.hpp"
#include "slam/deviations/map_against_plan.hpp"

namespace isg::run {

// The map against the plan (slam::measureMapAgainstPlan, docs/deviations.md, "Where the map
// disagrees with the plan") of a run: its thinned scans placed in the plan by its final trajectory
// (forEachPlacedMapPoint). One per level of `levels` (the levels the report judged), in their
// order; none when the run has no plan, never placed its map in it, or kept no scan.
std::vector<slam::LevelAgainstPlan> mapAgainstPlan(const RunRecord& run,
                                                   const std::vector<std::string>& levels,
                                                   const slam::MapAgainstPlanOptions& options = {});

// metrics.json's map_to_plan.levels entry of a level: its numbers, the stretches lying off by
// `off_m` or more (by default 4 cm, twice the localizer's own accuracy: slam::kOffClassBounds[1])
// with their length, and the farthest stretch.
RunMetrics::MapToPlan::Level levelSummary(const slam::LevelAgainstPlan& level,
                                          double off_m = slam::kOffClassBounds[1]);

}  // namespace isg::run
