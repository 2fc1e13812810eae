#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "bim/agraph.hpp"

namespace isg::slam {

// Where the map's points lie off the plan's faces, per level (docs/deviations.md, "Where the map
// disagrees with the plan"): the map-against-plan measure placed. Measured here
// (measureMapAgainstPlan) from the map's points as whoever holds them gives them (a run: its
// thinned scans placed by its final trajectory, run/map_to_plan_levels.cpp); the deviation report
// carries it into deviations.json, deviations.svg and the run's MCAP.
struct FaceStretch {
  std::string surface;  // the plan face's id ("W3:left")
  Eigen::Vector2d start = Eigen::Vector2d::Zero(), end = Eigen::Vector2d::Zero();  // in B
  std::size_t points = 0;
  // Of the points whose nearest face this is: their mean signed distance from it (positive in
  // front of it, in the space it looks at) and their root mean square.
  double mean_m = 0.0;
  double rms_m = 0.0;
};

struct LevelAgainstPlan {
  std::string level;
  std::size_t points = 0;   // the map's points in a wall surface's height band on this level
  double near_share = 0.0;  // of those, within `cutoff_m` of a face
  double cutoff_m = 0.0;
  // Of the near points' distances to their face, to the millimetre.
  double median_m = 0.0, p95_m = 0.0;
  // Stretches of each exposed face that enough near points fell on, along the faces.
  std::vector<FaceStretch> stretches;
};

// A point counts when it lies in some wall surface's height band, `margin_m` clear of the
// surface's bottom and top (floor and ceiling are not walls); it is near the plan when an exposed
// face segment of a surface whose band holds it lies within `cutoff_m` in the plane. A face is
// cut into equal stretches of at most `stretch_m`; a stretch is reported when at least
// `min_points` near points fell on it: fewer say little of where a face lies (a ring crossing it
// once leaves 10–20 points a metre).
struct MapAgainstPlanOptions {
  double cutoff_m = 0.3;
  double margin_m = 0.2;
  double stretch_m = 1.0;
  std::size_t min_points = 30;
};

// Gives each of the map's points, in the plan frame B, to `visit`, one at a time (a long run's
// map is never held placed as a whole).
using MapPointSource =
    std::function<void(const std::function<void(const Eigen::Vector3d&)>& visit)>;

// One per level of `levels` (the levels the report judges), in their order. A point belongs to
// the level of the face nearest to it, or, near none, of the highest floor at or below it
// (bim::floorAt); a point of a level not listed is nobody's. None when the source gave no point.
std::vector<LevelAgainstPlan> measureMapAgainstPlan(const bim::AGraph& plan,
                                                    const std::vector<std::string>& levels,
                                                    const MapPointSource& map_points,
                                                    const MapAgainstPlanOptions& options = {});

// How far off a stretch lies, |mean_m|, in four classes for the pictures: 0 within 2 cm (the
// localizer's own accuracy), 1 to 4 cm, 2 to 8 cm (beyond the report's shift threshold of 6 cm
// lies a wall built off, or the map off there), 3 beyond.
inline constexpr double kOffClassBounds[3] = {0.02, 0.04, 0.08};
inline int offClass(double mean_m) {
  int c = 0;
  while (c < 3 && std::abs(mean_m) >= kOffClassBounds[c]) ++c;
  return c;
}

}  // namespace isg::slam
