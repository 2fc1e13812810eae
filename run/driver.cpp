#include "run/driver.hpp"

#include <algorithm>
#include <chrono>

#include "run/map_samples.hpp"

namespace isg::run {

const sensors::ImuSample* LocalizerDriver::nextImu() {
  if (imu_ == nullptr) return nullptr;
  while (next_imu_ >= imu_->size()) {
    if (!imu_more_) return nullptr;
    imu_chunk_ = imu_more_();
    if (imu_chunk_.empty()) {
      imu_more_ = nullptr;
      return nullptr;
    }
    imu_ = &imu_chunk_;
    next_imu_ = 0;
  }
  return &(*imu_)[next_imu_];
}

void LocalizerDriver::pushOdometryUntil(double t) {
  for (;;) {
    const bool odometry = next_odometry_ < odometry_.size() && odometry_.time(next_odometry_) <= t;
    const sensors::ImuSample* sample = nextImu();
    const bool imu = sample != nullptr && sample->t <= t;
    if (!odometry && !imu) return;
    // The earlier first; odometry before an IMU sample of the same instant.
    if (odometry && (!imu || odometry_.time(next_odometry_) <= sample->t)) {
      const common::StampedPose pose = odometry_[next_odometry_];
      localizer_.pushOdometry({pose.t, pose.pose});
      ++next_odometry_;
    } else {
      localizer_.pushImu(*sample);
      ++next_imu_;
    }
  }
}

bool LocalizerDriver::wants(double stamp) {
  pushOdometryUntil(stamp + scan_period_);
  return localizer_.wantsScan(stamp);
}

void LocalizerDriver::feed(const sensors::Scan& scan) {
  pushOdometryUntil(scan.stamp + scan_period_);
  localizer_.pushScan(scan);
  record();
}

void LocalizerDriver::skip(double stamp) {
  pushOdometryUntil(stamp + scan_period_);
  record();
}

void LocalizerDriver::record() {
  const auto pose = localizer_.poseInMap();
  if (!pose) return;
  if (!estimate_map_.empty() && estimate_map_.back().t >= pose->stamp) return;
  estimate_map_.push_back({pose->stamp, pose->M_T_R});
  PoseState state = PoseState::kLost;
  if (const auto B_T_M = localizer_.mapInPlan()) {
    if (!localized_at_) localized_at_ = pose->stamp;
    B_T_M_ = *B_T_M;
    state = localizer_.planConfirms() ? PoseState::kLocalized : PoseState::kTracking;
  } else if (!B_T_M_) {
    return;  // never localized yet: no pose in B
  }
  // Lost: the last B_T_M over the map that carries on (M continues across the localizer's
  // restarts), flagged, so that the estimate never goes silent once it has spoken.
  estimate_.push_back({pose->stamp, *B_T_M_ * pose->M_T_R});
  estimate_states_.push_back(state_track_.next(state, pose->M_T_R.translation()));
  last_state_ = state;
  if (state == PoseState::kLocalized) {
    confirmed_B_T_M_ = B_T_M_;
  } else if (state == PoseState::kLost) {
    confirmed_B_T_M_.reset();
  }
}

std::optional<Eigen::Isometry3d> LocalizerDriver::confirmedMapInPlan() const {
  // A localizer that states no confirmation (every pose localized) and a run before any pose
  // agree with the last word.
  if (!last_state_ || *last_state_ == PoseState::kLocalized) return B_T_M_;
  return confirmed_B_T_M_;
}

RunRecord runLocalizer(RunSetup setup, slam::Localizer& localizer, sensors::SensorStreams streams,
                       sensors::ScanSource& scans, const RunProgress& progress,
                       const RunObserver& observer) {
  const auto start = std::chrono::steady_clock::now();
  RunRecord record;
  record.setup = std::move(setup);
  record.streams = std::move(streams);
  const sensors::SensorStreams& s = record.streams;
  LocalizerDriver driver(localizer, s.odometry, s.scan_period, &s.imu, s.imu_more);
  const int total = int(s.scan_stamps.size());
  driver.reserve(std::size_t(total));
  int read = 0;
  using Clock = std::chrono::steady_clock;
  Clock::duration in_localizer{}, waiting{};
  for (int k = 0; k < total; ++k) {
    const double stamp = s.scan_stamps[k];
    auto mark = Clock::now();
    const bool wanted = driver.wants(stamp);
    auto now = Clock::now();
    in_localizer += now - mark;
    mark = now;
    sensors::Scan scan;
    if (wanted) {
      scan = scans.scan(k);
      scan.stamp = stamp;
      now = Clock::now();
      waiting += now - mark;
      mark = now;
      driver.feed(scan);
      ++read;
      offerMapSample(record, scan);
    } else {
      scans.skip(k);
      now = Clock::now();
      waiting += now - mark;
      mark = now;
      driver.skip(stamp);
    }
    in_localizer += Clock::now() - mark;
    if (observer) observer(wanted ? &scan : nullptr, localizer, driver);
    if (progress) progress(k + 1, total, localizer);
  }
  // Fed: nothing after the loop reads it (RunRecord::streams).
  record.streams.imu = {};
  record.streams.imu_more = nullptr;
  record.estimate_map = driver.takeEstimateMap();
  record.estimate = driver.takeEstimate();
  record.estimate_states = driver.takeEstimateStates();
  record.localized_at = driver.localizedAt();
  record.scans = total;
  record.scans_read = read;
  record.localizer_seconds = std::chrono::duration<double>(in_localizer).count();
  record.scan_wait_seconds = std::chrono::duration<double>(waiting).count();
  record.stage_times = scans.stageTimes();
  const sensors::StageTimes localizer_stages = localizer.stageTimes();
  record.stage_times.add(localizer_stages);
  record.stage_times.add("localizer, other",
                         std::max(0.0, record.localizer_seconds - localizer_stages.total()));
  record.graph = localizer.graph();
  record.search_status = localizer.searchStatus();
  record.status_changes = localizer.statusChanges();
  record.map = localizer.mapDiagnostics();
  record.final_B_T_M = driver.confirmedMapInPlan();
  record.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return record;
}

}  // namespace isg::run
