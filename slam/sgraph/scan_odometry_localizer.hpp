#pragma once

#include <memory>
#include <optional>
#include <string>

#include "slam/localizer.hpp"
#include "slam/sgraph/scan_odometry.hpp"

namespace isg::slam {

// Any localizer run on a robot without odometry (docs/slam.md, "Without odometry"): every scan
// goes first to ScanOdometry, whose pose at the scan's stamp (and, extrapolated, at the end of its
// turn) is given to the localizer as its odometry before the scan itself. The IMU, when there is
// one, goes to ScanOdometry; odometry pushed from outside goes to the localizer unchanged.
class ScanOdometryLocalizer : public Localizer {
 public:
  ScanOdometryLocalizer(std::unique_ptr<Localizer> inner, const Eigen::Isometry3d& R_T_L,
                        const Eigen::Isometry3d& R_T_I, const ScanOdometryOptions& options = {});

  std::string name() const override { return inner_->name(); }
  void pushOdometry(const sensors::Odometry& odometry) override { inner_->pushOdometry(odometry); }
  void pushImu(const sensors::ImuSample& sample) override {
    odometry_.addImu(sample);
    inner_->pushImu(sample);  // for its own use of gravity (the S-Graph's)
  }
  void pushScan(const sensors::Scan& scan) override;
  // Every scan makes the odometry.
  bool wantsScan(double) const override { return true; }
  std::optional<sensors::Odometry> poseInMap() const override { return inner_->poseInMap(); }
  std::optional<Eigen::Isometry3d> mapInPlan() const override { return inner_->mapInPlan(); }
  bool planConfirms() const override { return inner_->planConfirms(); }
  nlohmann::json graph() const override;
  std::optional<std::string> searchStatus() const override { return inner_->searchStatus(); }
  std::vector<StatusChange> statusChanges() const override { return inner_->statusChanges(); }
  std::optional<MapDiagnostics> mapDiagnostics() const override { return inner_->mapDiagnostics(); }
  sensors::StageTimes stageTimes() const override;

 private:
  std::unique_ptr<Localizer> inner_;
  ScanOdometry odometry_;
  std::optional<double> last_pushed_;
  sensors::StageTimes times_;  // "scan odometry"
};

}  // namespace isg::slam
