#pragma once

#include <Eigen/Geometry>
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
};

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
