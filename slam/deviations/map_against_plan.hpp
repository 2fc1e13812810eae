#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace isg::slam {

// Where the map's points lie off the plan's faces, per level (docs/deviations.md, "Where the map
// disagrees with the plan"): the map-against-plan measure placed. Filled by whoever holds the
// map's points (the run's thinned scans, run/map_against_plan.cpp); the deviation report carries
// it into deviations.json, deviations.svg and the run's MCAP.
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
