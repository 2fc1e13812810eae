#include "slam/sgraph/scan_odometry_localizer.hpp"

namespace isg::slam {

ScanOdometryLocalizer::ScanOdometryLocalizer(std::unique_ptr<Localizer> inner,
                                             const Eigen::Isometry3d& R_T_L,
                                             const Eigen::Isometry3d& R_T_I,
                                             const ScanOdometryOptions& options)
    : inner_(std::move(inner)), odometry_(R_T_L, R_T_I, options) {}

void ScanOdometryLocalizer::pushScan(const sensors::Scan& scan) {
  sensors::StageClock clock(times_, "scan odometry");
  const Eigen::Isometry3d pose = odometry_.addScan(scan);
  // The odometry has read the scan's times already: another pass over its points cost as much as
  // a tenth of the odometry's own (a scan is larger than the processor's caches).
  const float last = float(odometry_.lastScanSpan());
  clock.stop();
  const auto push = [&](double t, const Eigen::Isometry3d& M_T_R) {
    if (last_pushed_ && t <= *last_pushed_) return;
    inner_->pushOdometry({t, M_T_R});
    last_pushed_ = t;
  };
  push(scan.stamp, pose);
  // The turn after the stamp, at the latest velocity; a microsecond short of its end, so that the
  // next scan's own pose (at that instant, the next stamp) still follows it.
  if (last > 1e-5f) {
    const double end = scan.stamp + double(last) - 1e-6;
    push(end, odometry_.predict(end));
  }
  inner_->pushScan(scan);
}

nlohmann::json ScanOdometryLocalizer::graph() const {
  nlohmann::json out = inner_->graph();
  if (out.is_object()) {
    out["odometry"] = {{"source", odometry_.hasImu() ? "LiDAR and IMU" : "LiDAR"},
                       {"scans_registered", odometry_.registered()},
                       {"scans_agreeing", odometry_.agreed()}};
    // The start's up turned from gravity's by the first scan's walls and floors (null: kept).
    if (const auto turned = odometry_.startLevelled()) {
      out["odometry"]["start_levelled_deg"] = *turned * 180.0 / 3.14159265358979323846;
    } else {
      out["odometry"]["start_levelled_deg"] = nullptr;
    }
  }
  return out;
}

sensors::StageTimes ScanOdometryLocalizer::stageTimes() const {
  sensors::StageTimes out = times_;
  out.add(inner_->stageTimes());
  return out;
}

}  // namespace isg::slam
