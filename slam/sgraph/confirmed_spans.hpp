#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "slam/sgraph/plane_map.hpp"

namespace isg::slam {

// The parts of a map wall its observations confirm (MapWall::confirmed), in metres along it from
// m.start: where at least two of `spans` saw it (each an observation's ends in M, or one of its
// pieces: PlaneObservation::pieces), and at least kConfirmShare of the most that saw any part
// within kConfirmNear of it. In order and apart. A wall seen once is confirmed where that once
// saw it. docs/deviations.md, "Progress".
std::vector<std::pair<double, double>> confirmedSpans(
    const MapPlane& m, const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& spans);

}  // namespace isg::slam
