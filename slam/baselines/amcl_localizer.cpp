#include "slam/baselines/amcl_localizer.hpp"

#include <cstdio>

namespace isg::slam {

namespace {

const bim::Level& levelOf(const bim::Plan& plan, const std::string& level) {
  const bim::Level* found = plan.findLevel(level);
  if (found == nullptr) throw std::invalid_argument("the plan has no level \"" + level + "\"");
  return *found;
}

}  // namespace

AmclLocalizer::AmclLocalizer(const bim::Plan& plan, const std::string& level,
                             const Eigen::Isometry3d& R_T_L, const AmclOptions& options,
                             std::uint64_t seed)
    : options_(options),
      R_T_L_(R_T_L),
      elevation_(levelOf(plan, level).elevation),
      map_(std::make_unique<LikelihoodField>(plan, level, options.map)),
      filter_(*map_, options.filter, seed) {
  if (map_->freeCells().empty()) {
    throw std::invalid_argument("level \"" + level + "\" has no free space to localize in");
  }
}

bool AmclLocalizer::wantsScan(double) const {
  if (!latest_) return false;               // no odometry yet
  if (!last_update_odometry_) return true;  // global localization: the first scan always updates
  const Pose2 odometry = planarPose(latest_->M_T_R);
  const OdometryMotion moved = decomposeOdometry(*last_update_odometry_, odometry);
  const double turned = std::abs(common::angleDifference(odometry.yaw, last_update_odometry_->yaw));
  return moved.trans >= options_.update_min_d || turned >= options_.update_min_a;
}

void AmclLocalizer::pushScan(const sensors::Scan& scan) {
  if (!wantsScan(scan.stamp)) return;
  const Pose2 odometry = planarPose(latest_->M_T_R);
  if (!last_update_odometry_) {
    filter_.initUniform();
  } else {
    filter_.motionUpdate(*last_update_odometry_, odometry);
  }
  last_update_odometry_ = odometry;
  filter_.sensorUpdate(planarScan(scan, R_T_L_, options_.scan).endpoints);
  if (++updates_ % std::max(1, options_.resample_interval) == 0) filter_.resample();
  // The estimate is the heaviest cluster's mean; it stands for the robot only while the rule of
  // AmclOptions holds.
  B_T_M_.reset();
  if (filter_.clusters().empty()) return;
  const ParticleCluster& best = filter_.clusters().front();
  const Eigen::Matrix2d& C = best.covariance;  // its larger eigenvalue, in closed form
  const double largest = 0.5 * (C(0, 0) + C(1, 1)) + std::hypot(0.5 * (C(0, 0) - C(1, 1)), C(0, 1));
  if (best.weight >= options_.localized_weight &&
      std::sqrt(std::max(0.0, largest)) <= options_.localized_std &&
      std::sqrt(best.yaw_variance) <= options_.localized_yaw_std) {
    // B_T_M carries the odometry since this update to the estimate, as AMCL's map → odom.
    B_T_M_ = toIsometry(best.mean, elevation_) * toIsometry(odometry).inverse();
  }
}

std::optional<std::string> AmclLocalizer::searchStatus() const {
  if (filter_.clusters().empty()) return std::nullopt;
  char text[96];
  std::snprintf(text, sizeof text, "%zu particles, heaviest cluster %.0f %%",
                filter_.particles().size(), 100.0 * filter_.clusters().front().weight);
  return std::string(text);
}

nlohmann::json AmclLocalizer::graph() const {
  nlohmann::json clusters = nlohmann::json::array();
  for (std::size_t i = 0; i < std::min<std::size_t>(5, filter_.clusters().size()); ++i) {
    const ParticleCluster& c = filter_.clusters()[i];
    clusters.push_back({{"weight", c.weight},
                        {"particles", c.count},
                        {"mean", {c.mean.x, c.mean.y, c.mean.yaw}},
                        {"std_xy",
                         {std::sqrt(std::max(0.0, c.covariance(0, 0))),
                          std::sqrt(std::max(0.0, c.covariance(1, 1)))}},
                        {"std_yaw", std::sqrt(c.yaw_variance)}});
  }
  return {{"method", name()},
          {"updates", updates_},
          {"particles", filter_.particles().size()},
          {"w_slow", filter_.wSlow()},
          {"w_fast", filter_.wFast()},
          {"localized", B_T_M_.has_value()},
          {"clusters", clusters}};
}

}  // namespace isg::slam
