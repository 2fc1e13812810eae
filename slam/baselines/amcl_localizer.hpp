#pragma once

#include <memory>

#include "bim/plan.hpp"
#include "slam/baselines/amcl_filter.hpp"
#include "slam/baselines/planar_scan.hpp"
#include "slam/localizer.hpp"

namespace isg::slam {

struct AmclOptions {
  ParticleFilterOptions filter;
  LikelihoodFieldOptions map;
  PlanarScanOptions scan;
  // The filter updates once the odometry has moved this far since its last update (nav2).
  double update_min_d = 0.25;  // metres
  double update_min_a = 0.2;   // radians
  int resample_interval = 1;   // resample every n-th update (nav2)
  // Localized: the heaviest cluster holds at least this share of the particles' weight ...
  double localized_weight = 0.9;
  // ... and its standard deviations are within these: nav2's convergence distance (0.5 m) in
  // the larger direction of x, y, and 20° of heading. With nav2's motion noise a converged cloud
  // spreads about 0.25 m and 15° (one σ) while the robot walks.
  double localized_std = 0.5;
  double localized_yaw_std = 20.0 * M_PI / 180.0;
};

// 2D Monte Carlo localization as ROS AMCL does it, in the plan's occupancy grid, from a global
// (uniform) start: the 2D baseline of the paper's Table I (docs/baselines.md).
class AmclLocalizer : public Localizer {
 public:
  AmclLocalizer(const bim::Plan& plan, const std::string& level, const Eigen::Isometry3d& R_T_L,
                const AmclOptions& options, std::uint64_t seed);

  std::string name() const override { return "amcl"; }
  void pushOdometry(const sensors::Odometry& odometry) override { latest_ = odometry; }
  void pushScan(const sensors::Scan& scan) override;
  bool wantsScan(double stamp) const override;
  std::optional<sensors::Odometry> poseInMap() const override { return latest_; }
  std::optional<Eigen::Isometry3d> mapInPlan() const override { return B_T_M_; }
  nlohmann::json graph() const override;
  std::optional<std::string> searchStatus() const override;

  const ParticleFilter& filter() const { return filter_; }
  int updates() const { return updates_; }

 private:
  AmclOptions options_;
  Eigen::Isometry3d R_T_L_;
  double elevation_ = 0.0;
  std::unique_ptr<LikelihoodField> map_;
  ParticleFilter filter_;
  std::optional<sensors::Odometry> latest_;
  std::optional<Pose2> last_update_odometry_;
  int updates_ = 0;
  std::optional<Eigen::Isometry3d> B_T_M_;
};

}  // namespace isg::slam
