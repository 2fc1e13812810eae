#include "run/driver.hpp"

#include <chrono>

namespace isg::run {

void LocalizerDriver::feed(const slam::Scan& scan) {
  while (next_odometry_ < odometry_.size() &&
         odometry_[next_odometry_].t <= scan.stamp + scan_period_) {
    localizer_.pushOdometry({odometry_[next_odometry_].t, odometry_[next_odometry_].pose});
    ++next_odometry_;
  }
  localizer_.pushScan(scan);
  const auto pose = localizer_.poseInMap();
  if (!pose) return;
  if (!estimate_map_.empty() && estimate_map_.back().t >= pose->stamp) return;
  estimate_map_.push_back({pose->stamp, pose->M_T_R});
  if (const auto B_T_M = localizer_.mapInPlan()) {
    if (!localized_at_) localized_at_ = pose->stamp;
    estimate_.push_back({pose->stamp, *B_T_M * pose->M_T_R});
  }
}

RunRecord runLocalizer(RunSetup setup, slam::Localizer& localizer, SensorStreams streams,
                       ScanSource& scans, const RunProgress& progress) {
  const auto start = std::chrono::steady_clock::now();
  RunRecord record;
  record.setup = std::move(setup);
  record.streams = std::move(streams);
  const SensorStreams& s = record.streams;
  LocalizerDriver driver(localizer, s.odometry, s.scan_period);
  const int total = int(s.scan_stamps.size());
  for (int k = 0; k < total; ++k) {
    slam::Scan scan = scans.scan(k);
    scan.stamp = s.scan_stamps[k];
    driver.feed(scan);
    if (progress) progress(k + 1, total, localizer);
  }
  record.estimate_map = driver.estimateMap();
  record.estimate = driver.estimate();
  record.localized_at = driver.localizedAt();
  record.scans = total;
  record.graph = localizer.graph();
  record.search_status = localizer.searchStatus();
  record.status_changes = localizer.statusChanges();
  record.map = localizer.mapDiagnostics();
  record.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return record;
}

}  // namespace isg::run
