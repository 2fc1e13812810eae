#pragma once

#include "slam/isgraph/graph_matching.hpp"
#include "slam/sgraph/sgraph.hpp"

namespace isg::slam {

// The S-Graph as the matcher sees it (walls of a minimum height, confirmed rooms, transitions),
// of the floor the robot stands on (the latest one it stood on, while on the stairs).
MatchInput matchInputOf(const SGraph& graph, double min_wall_height);

// The planes of `input` that the latest `keyframes` keyframes of `graph` observed (no rooms).
MatchInput recentPlanesOf(const MatchInput& input, const SGraph& graph, int keyframes);

// The planes of `input` that the latest `keyframes` keyframes observed, each cut to the stretch
// they observed it over (their observations placed by their keyframes' estimates, R_T_L the
// sensor's mount, projected onto the plane): a wall judged where the robot sees it, not at the
// middle of all that was mapped of it — on a long wall of a bent map that middle is tens of
// metres away and off the plan by the bend, not by the building (docs/matching.md, "The merged
// graph bends"). The planes keep their own parameters; no rooms.
MatchInput recentStretchesOf(const MatchInput& input, const SGraph& graph,
                             const Eigen::Isometry3d& R_T_L, int keyframes);

// What the latest `keyframes` keyframes of `graph` saw of the walls of its current floor, each
// wall once, as its newest sighting placed by the keyframe's estimate (R_T_L: the sensor's
// mount): the part of the map about the robot as the robot holds it. A wall mapped long before
// and seen again keeps its old plane and extent in the map, bent with the odometry's drift since;
// its sighting now does not. Identified by the wall's plane index; no rooms.
MatchInput recentSightingsOf(const SGraph& graph, const Eigen::Isometry3d& R_T_L, int keyframes,
                             double min_wall_height);

}  // namespace isg::slam
