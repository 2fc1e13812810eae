#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "slam/sgraph/plane_voxel_map.hpp"
#include "slam/sgraph/scan_registration.hpp"

namespace isg::slam {

// The LiDAR odometry's registration (docs/slam.md, "Without odometry"): a scan, deskewed and
// downsampled, in L, against the planes of the odometry's voxel map, by point-to-plane ICP in
// x, y and yaw against the walls' planes (roll and pitch are the IMU's, the height held).
struct OdometryRegistration {
  // The correction to the predicted pose, in M: a turn by yaw about the base's predicted position,
  // then a translation. M_T_R = Δ · M_T_R_predicted (planarCorrection).
  Eigen::Vector3d correction = Eigen::Vector3d::Zero();  // dx, dy, dyaw
  double inlier_share = 0.0;                             // points near the map after registration
  int points = 0;                                        // scan points used
  int correspondences = 0;                               // at the last pass
  bool agrees = false;                                   // inlier_share ≥ min_inlier_share
  Eigen::Isometry3d apply(const Eigen::Isometry3d& M_T_R_predicted) const;
};

// `prior_information` (on dx, dy, dyaw) is the prediction's confidence. The options are the
// S-Graph registration's: correspondence tolerances, passes, Huber, σ, effective points, the
// agreement share.
OdometryRegistration registerToPlanes(const std::vector<Eigen::Vector3f>& scan_in_L,
                                      const Eigen::Isometry3d& M_T_R_predicted,
                                      const Eigen::Isometry3d& R_T_L, const PlaneVoxelMap& map,
                                      const Eigen::Matrix3d& prior_information,
                                      const ScanRegistrationOptions& options);

}  // namespace isg::slam
