#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "bim/agraph.hpp"
#include "slam/deviations/built_line.hpp"
#include "slam/deviations/viewpoint.hpp"

namespace isg::slam {

struct DeviationOptions;

// How much of a plan wall is built (docs/deviations.md, "Progress"): along its axis, the parts
// the map's walls stand on, the parts the sensor had in view with no map wall there (not built,
// or not yet), and the parts never in view.
enum class ProgressStatus { kBuilt, kPartlyBuilt, kNotBuilt, kNotSeen };
const char* toString(ProgressStatus status);

using Intervals = std::vector<std::pair<double, double>>;  // metres along the axis, in order

struct WallProgress {
  ProgressStatus status = ProgressStatus::kNotSeen;
  // The faces' exposed parts along the axis (door openings and the ends inside other walls
  // excepted), and their length: what there is to build and see.
  Intervals exposed;
  double planned_m = 0.0;
  double built_m = 0.0, not_built_m = 0.0, not_seen_m = 0.0;  // of planned_m
  Intervals built;  // where it stands, a door opening between two built parts bridged
};

// A plan wall's axis from `start` along `axis` (unit) over `length`; `evidence` the spans along it
// (metres from its start) of the map walls taken as its faces. `viewpoints`: where the sensor
// stood on the wall's level and what it saw past (for what was in view, as for a missing wall);
// `built` where the wall stands off its axis, its fitted line (FaceViews).
WallProgress measureProgress(const bim::AGraph& plan, const bim::WallNode& wall,
                             const Eigen::Vector2d& start, const Eigen::Vector2d& axis,
                             double length, const Intervals& evidence,
                             const std::vector<Viewpoint>& viewpoints,
                             const DeviationOptions& options, const BuiltLine& built = {});

// The length of the intersection of two sets of intervals, each in order and apart.
double overlapLength(const Intervals& a, const Intervals& b);

}  // namespace isg::slam
