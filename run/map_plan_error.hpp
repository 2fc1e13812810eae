#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "eval/ape.hpp"
#include "run/run_record.hpp"

namespace isg::run {

// The paper's measure for recordings without ground truth (its Table II): how far the map the run
// built lies from the plan's wall surfaces, once placed in the plan (docs/evaluation.md,
// "Map against the plan"). The map is the run's thinned scans (RunRecord::map_samples), each
// point placed by the method's final trajectory — its optimised keyframes carried between them by
// odometry, or its online estimate for methods without keyframes — and the map's final place in
// the plan. A point counts when it lies in the height band of some wall surface, `margin` clear
// of the surface's bottom and top (floor and ceiling are not walls); it is near the plan when an
// exposed wall segment of a surface whose band holds it lies within `cutoff` in the plane, and
// its error is that distance. Points farther are clutter, doors, what the glass let through or a
// wrong map, and are counted, not measured.
struct MapPlanErrorOptions {
  double cutoff = 0.3;  // m
  double margin = 0.2;  // m
};

struct MapPlanError {
  eval::Statistics distance;  // of the points near the plan, metres
  std::size_t points = 0;     // in a wall's height band
  double near_share = 0.0;    // of those, near the plan
};

// The run's thinned scans placed in the plan frame B as described above (none when the map was
// never placed in the plan), one point at a time, none kept: what the metric measures and the
// report draws, so that a long run's map is never held placed as a whole.
void forEachPlacedMapPoint(const RunRecord& run,
                           const std::function<void(const Eigen::Vector3d&)>& visit);

// Of those, the points in a wall surface's height band (`options.margin` clear of floor and
// ceiling): the map's walls, as the report draws them.
void forEachWallBandMapPoint(const RunRecord& run, const MapPlanErrorOptions& options,
                             const std::function<void(const Eigen::Vector3d&)>& visit);

// nullopt when the run has no plan, never placed its map in it, or kept no scan.
std::optional<MapPlanError> mapPlanError(const RunRecord& run,
                                         const MapPlanErrorOptions& options = {});

}  // namespace isg::run
