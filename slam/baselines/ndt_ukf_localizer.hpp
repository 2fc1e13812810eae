#pragma once

#include <memory>

#include "bim/plan.hpp"
#include "slam/baselines/unscented_kalman_filter.hpp"
#include "slam/localizer.hpp"
#include "slam/odometry_buffer.hpp"

namespace isg::slam {

// hdl_localization's design (Koide et al.) with PCL's NDT: each scan, downsampled, is registered
// by NDT to a map cloud of the plan, starting from the prediction of an unscented Kalman filter
// that carries the pose and velocity forward with the odometry; NDT's pose is the filter's
// measurement. A tracker: it is given its start pose (docs/baselines.md).
struct NdtUkfOptions {
  // The map cloud: the plan's exposed wall faces, floor to wall top, sampled on a grid of this
  // spacing (hdl's global map is downsampled at 0.1 m), each point ±map_relief off its face.
  double map_spacing = 0.1;
  double map_relief = 0.01;
  // Scan points within this of the floor or the ceiling (at the predicted pose) are dropped: the
  // walls-only map cannot explain them. 0 keeps them.
  double wall_band = 0.2;
  double scan_voxel = 0.4;      // hdl_localization: 0.1 (docs/baselines.md says why not here)
  double scan_min_range = 0.3;  // closer points are the robot itself
  // NDT as hdl_localization sets it up: 1 m cells; PCL's defaults otherwise.
  double ndt_resolution = 1.0;
  double ndt_step_size = 0.1;
  // hdl_localization's transformation epsilon is 0.01 m of step; PCL 1.13's NDT compares the
  // step's *squared* translation with its epsilon, so the same test is 0.01² here (0.01 would
  // stop every registration after its first step, as any step of at most 0.1 m passes).
  double ndt_epsilon = 1e-4;
  int ndt_max_iterations = 35;
  // The filter's noise, as hdl_localization's pose estimator: process noise per second on
  // position 1.0, on heading 0.5, on velocity 1.0 (times dt); measurement noise 0.01 on
  // position, 0.001 on heading; initial covariance 0.01.
  double process_position = 1.0;
  double process_yaw = 0.5;
  double process_velocity = 1.0;
  double measurement_position = 0.01;
  double measurement_yaw = 0.001;
  double initial_covariance = 0.01;
};

class NdtUkfLocalizer : public Localizer {
 public:
  // start_B_T_M: where the tracker believes its odometry frame lies in the plan at the start
  // (the true one, perturbed by the caller); its first pose is start_B_T_M · M_T_R.
  NdtUkfLocalizer(const bim::Plan& plan, const std::string& level, const Eigen::Isometry3d& R_T_L,
                  const Eigen::Isometry3d& start_B_T_M, const NdtUkfOptions& options = {});
  ~NdtUkfLocalizer() override;

  std::string name() const override { return "ndt-ukf"; }
  void pushOdometry(const sensors::Odometry& odometry) override;
  void pushScan(const sensors::Scan& scan) override;
  std::optional<sensors::Odometry> poseInMap() const override { return latest_; }
  std::optional<Eigen::Isometry3d> mapInPlan() const override { return B_T_M_; }
  nlohmann::json graph() const override;

  std::size_t mapPoints() const;

 private:
  struct Registration;  // PCL's NDT and the map cloud, kept out of this header

  NdtUkfOptions options_;
  Eigen::Isometry3d R_T_L_;
  Eigen::Isometry3d start_B_T_M_;
  std::unique_ptr<Registration> registration_;
  std::unique_ptr<UnscentedKalmanFilter> filter_;  // from the first odometry on
  OdometryBuffer odometry_;
  std::optional<sensors::Odometry> latest_;
  std::optional<sensors::Odometry> last_scan_odometry_;  // M_T_R at the last scan
  std::optional<Eigen::Isometry3d> B_T_M_;
  double floor_ = 0.0, ceiling_ = 0.0;  // the level's, in B
  int scans_ = 0;
  int registrations_ = 0;
  long iterations_ = 0;  // NDT's, summed over the registrations
  double last_fitness_ = 0.0;
  bool last_converged_ = false;
};

}  // namespace isg::slam
