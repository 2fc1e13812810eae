#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "slam/sgraph/plane_map.hpp"

namespace isg::slam {

// Which parts of a wall its observations confirm. `near_m` must stay below the progress report's
// DeviationOptions::progress_gap_m: where a part seen by few abuts one seen by many (an
// occluder's shadow), the stretch left unconfirmed is then shorter than a gap the report
// believes, and is bridged as not seen (run/tests/report_options_test.cpp holds the two to it).
struct ConfirmationOptions {
  double near_m = 0.5;  // m along the wall
  double share = 0.2;   // of the most observations that saw any part within near_m
};

// The parts of a map wall its observations confirm (MapWall::confirmed), in metres along it from
// m.start: where at least two of `spans` saw it (each an observation's ends in M, or one of its
// pieces: PlaneObservation::pieces), and at least options.share of the most that saw any part
// within options.near_m of it. In order and apart; each edge at the median of the observations'
// ends within options.near_m of it, never further out. A wall seen once is confirmed where that
// once saw it. docs/deviations.md, "Progress".
std::vector<std::pair<double, double>> confirmedSpans(
    const MapPlane& m, const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& spans,
    const ConfirmationOptions& options = {});

}  // namespace isg::slam
