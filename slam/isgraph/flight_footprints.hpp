#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "bim/agraph.hpp"

namespace isg::slam {

// Where a flight of stairs of the plan lies, from its faces in the A-Graph (docs/agraph.md: a
// flight's two sides are surfaces of the level it rises from): the robot changes floor only there.
struct FlightFootprint {
  std::string stair;
  Eigen::Vector2d bottom = Eigen::Vector2d::Zero();  // the middle of the sides' first ends
  Eigen::Vector2d top = Eigen::Vector2d::Zero();     // ... and of their second ends
  double half_width = 0.0;
  double z_low = 0.0, z_high = 0.0;  // the floors it joins

  // How far p lies outside the flight's rectangle (0 inside).
  double distance(const Eigen::Vector2d& p) const;
  // Whether the flight starts or ends on a floor at `elevation` (within `tolerance`).
  bool joins(double elevation, double tolerance) const;
};

// One footprint per flight whose two sides the A-Graph holds.
std::vector<FlightFootprint> flightFootprints(const bim::AGraph& plan);

}  // namespace isg::slam
