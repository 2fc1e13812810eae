#pragma once

#include <random>

#include "bim/scenario.hpp"
#include "sim/base_motion.hpp"
#include "sim/occupancy_grid.hpp"
#include "sim/route_planner.hpp"

namespace isg::sim {

// The scenario's kidnaps (robot.kidnap, docs/formats.md), added to a planned route and its
// trajectory: at each kidnap's time the robot is put down at the target (a room's goal point
// facing a heading drawn from `rng`, or the given pose), on the target's level, and goes on to
// the targets of its route it had not reached yet, in their order, by stairs to those on other
// levels; one it cannot reach from there is skipped (listed in route.skipped_rooms). Errors
// (InputError with /robot/kidnap/N/...): the route has already ended at the kidnap's time, or the
// target is less than kMinClearance from a wall, clutter or the outside of the building.
void planKidnaps(const bim::Scenario& scenario, const OccupancyGrid& grid, PlannedRoute& route,
                 BaseMotion& trajectory, std::mt19937_64& rng);

}  // namespace isg::sim
