#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "bim/scenario.hpp"
#include "common/input_error.hpp"

namespace isg::worlds {

// Where a replayed walk goes: each of its poses, and points at most kWalkStep apart on the
// straight step from one pose to the next (a walk recorded at 1 Hz crosses a 10 cm wall between
// two poses). `visit(point, line)` gets the line of the step's later pose; it returns false to
// stop.
inline constexpr double kWalkStep = 0.02;  // m
void forEachWalkPoint(const std::vector<bim::WalkPose>& walk,
                      const std::function<bool(const Eigen::Vector2d&, int)>& visit);

// "crossed": "opening" cuts a gap this wide about where the walk crossed a wall (wider when it
// crossed at a slant: the whole pass along the wall, plus half of this on each side), widened
// over any door or window it reaches. A part of the wall left shorter than kMinWallPart beside a
// gap is taken as not built too.
inline constexpr double kCrossingOpeningWidth = 0.9;  // m, a door's
inline constexpr double kMinWallPart = 0.1;           // m

// A recorded walk goes where it went (docs/simulation.md, "Replayed walks"): the planned walls
// and columns of the robot's level that a trajectory route passes through are taken as not built
// on the day of the walk (robot.route "crossed": "not_built", the default) — added to the
// scenario's as_built.missing_walls / missing_columns — or, for walls with "crossed": "opening",
// as built in part with a door-wide gap where the walk crossed (as_built.shortened_walls). Each
// pass is kept in robot.route.crossings, and each element is said once on `warnings` with where
// the walk crossed it. Extra walls and clutter boxes of the scenario's own as_built stay: a walk
// through them is refused later (sim::checkWalkClear), as is everything with "crossed": "refuse".
// Other routes are left as they are.
void takeCrossedSolids(bim::Scenario& scenario, common::Warnings* warnings);

}  // namespace isg::worlds
