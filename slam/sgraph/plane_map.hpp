#pragma once

#include <Eigen/Geometry>
#include <limits>
#include <utility>
#include <vector>

#include "bim/plane.hpp"
#include "slam/sgraph/plane_extraction.hpp"

namespace isg::slam {

// A wall plane of the S-Graph's map, in the map frame M: its plane and how far along it has been
// seen (a segment, in M, at floor-independent height).
struct MapPlane {
  bim::Plane plane;
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  Eigen::Vector2d end = Eigen::Vector2d::Zero();
  int observations = 0;
  double z_min = 0.0, z_max = 0.0;  // heights at which it has been seen, in M
  // The lowest height in M at which rays were seen passing over its top (+∞: never), and how
  // many observations found its top beyond the sensor's view of it.
  double top_seen_z = std::numeric_limits<double>::infinity();
  int tops_beyond_view = 0;
};

// The plane's heights and top edge after one more observation (already in M).
void addHeights(MapPlane& plane, const PlaneObservation& observation_in_M);
// Two map planes found to be one: the kept one takes the dropped one's heights and top edges.
void mergeHeights(MapPlane& kept, const MapPlane& dropped);

// Whether a map plane can be a wall rather than a box of clutter: seen over at least
// `min_height`, or never seen to end below that height while at least once its top lay beyond
// the sensor's view (a sensor low on the robot sees a near wall over less than a metre; a box is
// overshot by the rings above it as soon as the robot stands back from it).
bool seenAsWall(const MapPlane& plane, double min_height);

struct AssociationOptions {
  double max_angle_deg = 10.0;  // between normals (planes facing away are different surfaces)
  // Between the planes' distances from the observation's centroid. Distinct parallel walls 0.3 m
  // apart must never merge, so this stays well below 0.3.
  double max_distance = 0.12;
  // Observed extent and map extent may be this far apart along the wall and still be one surface
  // (the gap a doorway leaves); farther, they are coplanar but separate walls.
  double max_gap = 1.0;
  // A map plane reaches at most this far along its wall (m; 0: without bound). The map bends
  // with the drift it was made with, and one plane cannot: a corridor wall two hundred metres
  // long kept as one plane is fitted to keyframes of very different drift, sits off the plan
  // where the robot is and is released from the merge as "built off" (docs/slam.md, "Wall planes
  // in pieces"). Beyond the bound a wall goes on as a new plane, tied to the plan on its own. The
  // bound is about the walk of the merge's window (25 keyframes a couple of metres apart), so a
  // plane is fitted to keyframes of about one drift.
  double max_length = 40.0;
};

// The map plane that an observation (already expressed in M) belongs to, or -1 for a new one:
// normals within max_angle_deg, the observation's centroid within max_distance of the map plane,
// extents overlapping or at most max_gap apart, and — where together they would reach beyond
// max_length — the observation's centroid within the map plane's extent; among several, the
// nearest.
int associate(const PlaneObservation& observation_in_M, const std::vector<MapPlane>& map,
              const AssociationOptions& options = {});

// The map plane's extent grown to take in an observation (in M) associated with it, along the
// plane: by at most what max_length leaves (0: without bound), shared between the two ends in
// proportion to what the observation adds at each. A plane that already reaches max_length keeps
// its extent, so a wall walked along goes on as a new plane rather than moving this one.
void extend(MapPlane& plane, const PlaneObservation& observation_in_M, double max_length);

// A new map plane from an observation (in M) that no map plane took: its extent is the
// observation's, at most max_length (0: without bound) about the observation's centroid.
MapPlane newMapPlane(const PlaneObservation& observation_in_M, double max_length);

// The unit direction along a wall plane: horizontal, across its normal (x when the plane is
// horizontal).
Eigen::Vector2d alongWall(const bim::Plane& plane);

// The map plane's ends laid on the plane as it stands now, each moved along the plane's
// horizontal normal only (their places along it kept). extend() lays them on the plane as it stood
// when the plane was last observed; the optimizer moves the plane afterwards with the keyframes
// that saw it, and on a sheared office the ends of a wall seen from 50 keyframes had been left
// 6–8 cm off its plane, up to 25 cm on walls 24–36 m long (docs/deviations.md, "Evidence").
std::pair<Eigen::Vector2d, Eigen::Vector2d> endsOnPlane(const MapPlane& plane);

// An observation (in the LiDAR frame) expressed in M, given M_T_L.
PlaneObservation toMap(const PlaneObservation& observation, const Eigen::Isometry3d& M_T_L);

}  // namespace isg::slam
