#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "slam/sgraph/plane_voxel_map.hpp"
#include "slam/sgraph/scan_registration.hpp"

namespace isg::slam {

// The LiDAR odometry's registration (docs/slam.md, "Without odometry"): a scan, deskewed and
// downsampled, in L, against the planes of the odometry's voxel map, by point-to-plane ICP in
// x, y and yaw against the walls' planes (roll and pitch are the IMU's, the height the level
// planes': levelOffset below).
// `prior_information` (on dx, dy, dyaw) is the prediction's confidence. The options are the
// S-Graph registration's: correspondence tolerances, passes, Huber, σ, effective points, the
// agreement share. The result is the S-Graph registration's, its correction applied the same way;
// `information` is the last pass's, and `inlier_share_predicted` is not measured here (zero).
RegistrationResult registerToPlanes(const std::vector<Eigen::Vector3f>& scan_in_L,
                                    const Eigen::Isometry3d& M_T_R_predicted,
                                    const Eigen::Isometry3d& R_T_L, const PlaneVoxelMap& map,
                                    const Eigen::Matrix3d& prior_information,
                                    const ScanRegistrationOptions& options);

// How far a scan (in L, placed at M_T_L) lies above the level planes of the odometry's map: the
// floors, ceilings, treads and tops it shares with the map (docs/slam.md, "Without odometry").
// Each point takes its plane as the registration does (PlaneVoxelMap::match within
// `max_distance`); those whose plane is level (|n_z| ≥ min_normal_z) give their height above it,
// averaged with Huber weights (`huber`, m). Three passes, each finding the planes again with the
// offset so far taken off.
struct LevelOffset {
  double offset = 0.0;  // m: the scan lies this far above the map's level planes
  double spread = 0.0;  // m: the points' spread about it (median absolute deviation, as a σ)
  int points = 0;       // scan points on a level plane, at the last pass
};
LevelOffset levelOffset(const std::vector<Eigen::Vector3f>& scan_in_L,
                        const Eigen::Isometry3d& M_T_L, const PlaneVoxelMap& map,
                        double max_distance, double huber, double min_normal_z);

}  // namespace isg::slam
