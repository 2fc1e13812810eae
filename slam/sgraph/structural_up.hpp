#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "slam/sgraph/plane_voxel_map.hpp"

namespace isg::slam {

// "Up" from one scan of a building: its walls stand vertical and its floors and ceilings lie
// level, so up is the direction most nearly across every wall patch and along every level one —
// the eigenvector of the least eigenvalue of Σ_walls w·n·nᵀ − Σ_level w·n·nᵀ over the scan's plane
// patches (n their normals, w their points). A patch is a wall when its normal lies within
// `class_angle_deg` of horizontal, level within that of vertical, judged against the guess and
// then against each pass's answer.
//
// Why: an IMU levels a sensor from gravity only at rest. A walk recorded mid-stride starts with
// the sensor accelerating — a hand-held camera's path swings at 2.5 m/s² where a real recording
// begins, 15° of tilt read as up — and the odometry's attitude filter, slow so that a walk's sway
// averages out, would keep most of that for a minute: the map tilted, its height climbing.
struct StructuralUpOptions {
  // The voxels whose planes are the patches: a metre, so that a patch holds some 25 of the
  // odometry's points (one per 0.2 m) and its normal is good to a few degrees.
  PlaneVoxelMapOptions patches = {.voxel = 1.0, .max_planarity = 0.02};
  double class_angle_deg = 30.0;
  // Refused beyond this from the guess: a start is not tilted further (a scan of no building).
  double max_tilt_deg = 30.0;
  int min_points = 200;  // on patches of either kind, at least
  // The answer is refused when the least eigenvalue is not clear of the next by this share of
  // all the patches' points: walls of one direction alone and nothing level leave up free to
  // turn about their normal.
  double min_gap_share = 0.1;
  int passes = 3;
};

// Up in the cloud's frame (unit), or nullopt when the scan cannot tell it (too few patches, one
// wall direction and nothing level, or an answer beyond max_tilt_deg of `up_guess`).
std::optional<Eigen::Vector3d> structuralUp(const std::vector<Eigen::Vector3f>& cloud,
                                            const Eigen::Vector3d& up_guess,
                                            const StructuralUpOptions& options = {});

}  // namespace isg::slam
