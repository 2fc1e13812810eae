#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "slam/sgraph/plane_voxel_map.hpp"
#include "slam/sgraph/scan_registration.hpp"

namespace isg::slam {

// The LiDAR odometry's registration (docs/slam.md, "Without odometry"): a scan, deskewed and
// downsampled, in L, against the planes of the odometry's voxel map, by point-to-plane ICP in
// x, y and yaw against the walls' planes (roll and pitch are the IMU's, the height held).
// `prior_information` (on dx, dy, dyaw) is the prediction's confidence. The options are the
// S-Graph registration's: correspondence tolerances, passes, Huber, σ, effective points, the
// agreement share. The result is the S-Graph registration's, its correction applied the same way;
// `information` is the last pass's, and `inlier_share_predicted` is not measured here (zero).
RegistrationResult registerToPlanes(const std::vector<Eigen::Vector3f>& scan_in_L,
                                    const Eigen::Isometry3d& M_T_R_predicted,
                                    const Eigen::Isometry3d& R_T_L, const PlaneVoxelMap& map,
                                    const Eigen::Matrix3d& prior_information,
                                    const ScanRegistrationOptions& options);

}  // namespace isg::slam
