#pragma once

#include <vector>

#include "run/map_plan_error.hpp"
#include "run/run_metrics.hpp"
#include "run/run_record.hpp"
#include "slam/deviations/map_against_plan.hpp"

namespace isg::run {

// The map-against-plan measure (mapPlanError) placed: per level and along each exposed face in
// stretches of at most `stretch_m`, so that a user sees where on a floor the map lies off the plan
// and why that floor localizes worse (docs/deviations.md, "Where the map disagrees with the
// plan"). A point belongs to the level of the face nearest to it, or, near none, of the highest
// floor at or below it. A stretch is reported when at least `min_points` fell on it: fewer say
// little of where a face lies (a ring crossing it once leaves 10–20 points a metre).
struct MapAgainstPlanOptions {
  MapPlanErrorOptions error;
  double stretch_m = 1.0;
  std::size_t min_points = 30;
};

// One per level of `levels` (the levels the report judged), in their order; none when the run
// has no plan, never placed its map in it, or kept no scan.
std::vector<slam::LevelAgainstPlan> mapAgainstPlan(const RunRecord& run,
                                                   const std::vector<std::string>& levels,
                                                   const MapAgainstPlanOptions& options = {});

// metrics.json's map_to_plan.levels entry of a level: its numbers, the stretches lying off by
// `off_m` or more (by default 4 cm, twice the localizer's own accuracy: slam::kOffClassBounds[1])
// with their length, and the farthest stretch.
RunMetrics::MapToPlan::Level levelSummary(const slam::LevelAgainstPlan& level,
                                          double off_m = slam::kOffClassBounds[1]);

}  // namespace isg::run
