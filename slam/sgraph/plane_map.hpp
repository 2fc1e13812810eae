#pragma once

#include <Eigen/Geometry>
#include <limits>
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
};

// The map plane that an observation (already expressed in M) belongs to, or -1 for a new one:
// normals within max_angle_deg, the observation's centroid within max_distance of the map plane,
// extents overlapping or at most max_gap apart; among several, the nearest.
int associate(const PlaneObservation& observation_in_M, const std::vector<MapPlane>& map,
              const AssociationOptions& options = {});

// An observation (in the LiDAR frame) expressed in M, given M_T_L.
PlaneObservation toMap(const PlaneObservation& observation, const Eigen::Isometry3d& M_T_L);

}  // namespace isg::slam
