#pragma once

#include <Eigen/Geometry>
#include <deque>
#include <optional>
#include <utility>
#include <vector>

#include "sensors/messages.hpp"
#include "slam/sgraph/attitude_filter.hpp"
#include "slam/sgraph/odometry_registration.hpp"
#include "slam/sgraph/plane_voxel_map.hpp"
#include "slam/sgraph/scan_registration.hpp"
#include "slam/sgraph/structural_up.hpp"

namespace isg::slam {

// Odometry for a robot that has none (a handheld sensor, a recording without wheel or leg
// odometry), made from the LiDAR and, when there is one, the IMU (docs/slam.md, "Without
// odometry"). The pose at each scan is predicted, then corrected by registering the scan to a
// local map of recent scans:
//   - roll and pitch: an attitude filter on the IMU (AttitudeFilter, time constant
//     `attitude_time_constant`, the gyroscope's bias estimated); level without an IMU;
//   - yaw: predicted by the gyroscope (without an IMU, by the last turn rate), corrected by the
//     registration;
//   - x, y: predicted at constant velocity, corrected by the registration;
//   - z: held from scan to scan (a height's velocity from the poses fed back as noise and ran
//     away where nothing level is seen), corrected by the scan's offset above the map's level
//     planes (levelOffset) when at least `min_level_points` points lie on them: floors,
//     ceilings and the treads of stairs, so that a sensor carried up or down stairs follows.
// The registration is point-to-plane ICP in x, y and yaw (slam/sgraph/odometry_registration.hpp)
// against the planes of a voxel map of the latest `local_map_keyframes` odometry keyframes' scans
// (one each `keyframe_distance` or `keyframe_angle`; slam/sgraph/plane_voxel_map.hpp), each scan
// first deskewed by the predicted motion. The map is updated as keyframes come and go, not
// rebuilt.
struct ScanOdometryOptions {
  // Its voxel, range limits, tolerances, passes and agreement share; its normals' options are the
  // S-Graph registration's alone (the map's planes have `map`).
  ScanRegistrationOptions registration;
  // The planes that register x, y and yaw: within about 6° of vertical (|n_z| ≤ this), not the
  // registration's 0.7. The height moves from scan to scan, and a plane's tilt turns its errors
  // into x and y (a floor voxel thickened by a few cm between keyframes fits tilted): at 0.7 the
  // odometry alone drifted twice as far on D3 by hand.
  double wall_max_normal_z = 0.1;
  PlaneVoxelMapOptions map;
  // Of each laser's returns, the odometry reads every return_stride-th (the first, the third, ...
  // at 2): a VLP-16's lasers fire 0.2° apart at 10 Hz, far finer than the registration's voxels,
  // and half the returns gave the same APE over the reference walks by hand (docs/performance.md)
  // at 0.8x the odometry's time. The S-Graph still reads every return of its keyframes' scans.
  int return_stride = 2;
  // The scan's points registered: one per this voxel (the map takes all at registration.voxel).
  double registration_voxel = 0.3;  // m
  double keyframe_distance = 0.3;   // m
  double keyframe_angle = 0.2;      // rad
  // How far the prediction is trusted, per scan: the registration's prior.
  double prior_sigma_translation = 0.3;  // m
  double prior_sigma_yaw_imu = 0.01;     // rad, gyroscope-predicted
  double prior_sigma_yaw = 0.1;          // rad, predicted by the last turn rate
  double prior_sigma_height = 0.02;      // m
  // The height is corrected from at least this many scan points on level planes, those whose
  // |n_z| is at least level_normal_z.
  int min_level_points = 20;
  double level_normal_z = 0.9;
  // The attitude filter's: long, so that a walker's sway and turns average out (2 s left roll and
  // pitch 0.8° off in a hand-held walk, which a floor 5 m away turns into 7 cm of height); the
  // gyroscope's bias is estimated, else a long time constant multiplies it.
  double attitude_time_constant = 30.0;  // s
  // With an IMU, the first scan's walls and floors level M (structuralUp): gravity alone levels
  // a start only at rest, and a recorded walk may start mid-stride.
  // Gravity is kept where the two agree within structural_up_min_turn_deg: at rest it is exact,
  // and the structure's answer good to a few tenths of a degree.
  StructuralUpOptions structural_up;
  double structural_up_min_turn_deg = 2.0;
  // The velocity of the prediction: the mean over this much of the latest poses.
  double velocity_window = 0.5;  // s
  double gravity = 9.81;
};

class ScanOdometry {
 public:
  ScanOdometry(const Eigen::Isometry3d& R_T_L, const Eigen::Isometry3d& R_T_I,
               const ScanOdometryOptions& options = {});

  // IMU samples in time order, up to the end of the next scan's turn before that scan.
  void addImu(const sensors::ImuSample& sample);
  // The base's pose in M at the scan's stamp (the first scan: M's origin, levelled by gravity when
  // the IMU has spoken); the scan is deskewed by the predicted motion and registered.
  Eigen::Isometry3d addScan(const sensors::Scan& scan);
  // The base's pose at `t` as predicted from the latest scan's: at the latest velocity, turned by
  // the gyroscope (or the last turn rate). Also the pose across the turn the latest scan spans.
  Eigen::Isometry3d predict(double t) const;
  bool hasImu() const { return !attitude_.empty(); }
  // The latest scan's last point's time after its stamp (0 for none later): the end of its turn.
  double lastScanSpan() const { return last_span_; }
  // Scans whose registration agreed with the local map, of those registered.
  int registered() const { return registered_; }
  int agreed() const { return agreed_; }
  // How far the first scan's structure turned the start's up from gravity's (rad), when it did
  // (an IMU, a scan of walls and floors, and the two apart by structural_up_min_turn_deg).
  std::optional<double> startLevelled() const { return start_levelled_; }

 private:
  struct Keyframe {
    PlaneVoxelMap::Contribution contribution;  // its scan's, in the map
    Eigen::Isometry3d M_T_R;
  };
  // Turns the attitude filter (and its history) about M's z: the registration's yaw correction.
  void turnYaw(double angle);
  // At the first scan: M levelled by the scan's walls and floors where they tell up
  // (structuralUp), the filter and `predicted` turned with it, M's heading kept the base's.
  void levelByStructure(const std::vector<Eigen::Vector3f>& cloud, Eigen::Isometry3d& predicted);
  // The change of height that the scan's points on the map's level planes ask of `pose` (the
  // registered pose), weighed against the prior: 0 with too few of them.
  double heightCorrection(const std::vector<Eigen::Vector3f>& cloud,
                          const Eigen::Isometry3d& pose) const;

  Eigen::Isometry3d R_T_L_, R_T_I_;
  ScanOdometryOptions options_;
  ScanRegistrationOptions wall_registration_;  // registration, wall_max_normal_z its walls'
  AttitudeFilter attitude_;
  // Poses at the latest two scans, and their velocity.
  std::optional<double> last_stamp_;
  Eigen::Isometry3d last_pose_ = Eigen::Isometry3d::Identity();
  Eigen::Vector3d velocity_ = Eigen::Vector3d::Zero();       // M, m/s
  double yaw_rate_ = 0.0;                                    // rad/s, without an IMU
  std::deque<std::pair<double, Eigen::Isometry3d>> recent_;  // poses over velocity_window
  std::deque<Keyframe> keyframes_;
  PlaneVoxelMap map_;  // of keyframes_
  VoxelIndex index_;   // the scan's voxels, reused from scan to scan
  double last_span_ = 0.0;
  int registered_ = 0, agreed_ = 0;
  std::optional<double> start_levelled_;
};

}  // namespace isg::slam
