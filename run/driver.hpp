#pragma once

#include <functional>
#include <optional>
#include <utility>

#include "run/estimate_states.hpp"
#include "run/run_record.hpp"
#include "sensors/scan_source.hpp"
#include "sensors/sensor_streams.hpp"
#include "slam/localizer.hpp"

namespace isg::run {

// Feeds a localizer as the robot would: for each scan, the odometry and the IMU up to the end of
// its turn (when the scan is complete), in time order, then the scan; and records what the
// localizer says.
class LocalizerDriver {
 public:
  // `imu`: the IMU's samples (none: no IMU); `imu_more`, when set, gives the ones after them, a
  // chunk at a time (sensors::SensorStreams::imu_more).
  LocalizerDriver(slam::Localizer& localizer, common::PoseSequence odometry, double scan_period,
                  const std::vector<sensors::ImuSample>* imu = nullptr,
                  std::function<std::vector<sensors::ImuSample>()> imu_more = {})
      : localizer_(localizer),
        odometry_(odometry),
        imu_(imu),
        imu_more_(std::move(imu_more)),
        scan_period_(scan_period) {}

  // Pushes the odometry up to the end of the turn starting at `stamp` and says whether the
  // localizer will read that scan (Localizer::wantsScan). Either feed or skip follows.
  bool wants(double stamp);
  void feed(const sensors::Scan& scan);
  // The scan at `stamp` goes unread: the odometry is pushed and the estimate recorded as feed
  // would, without the scan.
  void skip(double stamp);

  // Room for the estimates of `scans` scans (at most one pose each): hours of them, without a
  // vector's growth slack.
  void reserve(std::size_t scans) {
    estimate_map_.reserve(scans);
    estimate_.reserve(scans);
    estimate_states_.reserve(scans);
  }

  // The pose in M after each scan (stamped at the latest odometry), and in B from the first
  // localization on: by the localizer's B_T_M while it places its map, by the last one it gave
  // while it does not (lost); each pose's state beside it (run/estimate_states.hpp).
  const Trajectory& estimateMap() const { return estimate_map_; }
  const Trajectory& estimate() const { return estimate_; }
  const std::vector<EstimateState>& estimateStates() const { return estimate_states_; }
  std::optional<double> localizedAt() const { return localized_at_; }
  // The estimates moved out, once the run is over (a copy would hold them twice).
  Trajectory takeEstimateMap() { return std::move(estimate_map_); }
  Trajectory takeEstimate() { return std::move(estimate_); }
  std::vector<EstimateState> takeEstimateStates() { return std::move(estimate_states_); }
  // The localizer's last word on where its map lies in the plan.
  const std::optional<Eigen::Isometry3d>& mapInPlan() const { return B_T_M_; }
  // Where the plan last placed the map, as far as it still holds: the last word when the last
  // pose was localized; the word at the last localized pose when the estimate has only been
  // tracking since (the same map, carried without the plan's confirmation); none when it ended
  // lost (or never localized). What the run's report judges the map by (RunRecord::final_B_T_M).
  std::optional<Eigen::Isometry3d> confirmedMapInPlan() const;

 private:
  void pushOdometryUntil(double t);
  void record();
  const sensors::ImuSample* nextImu();  // the next IMU sample not yet pushed; null: none left

  slam::Localizer& localizer_;
  common::PoseSequence odometry_;               // a view: what it views outlives the driver
  const std::vector<sensors::ImuSample>* imu_;  // none: no IMU
  std::function<std::vector<sensors::ImuSample>()> imu_more_;
  std::vector<sensors::ImuSample> imu_chunk_;  // the latest chunk imu_more_ gave
  double scan_period_;
  std::size_t next_odometry_ = 0, next_imu_ = 0;
  Trajectory estimate_map_, estimate_;
  std::vector<EstimateState> estimate_states_;
  EstimateStateTrack state_track_;
  std::optional<double> localized_at_;
  std::optional<Eigen::Isometry3d> B_T_M_;
  // B_T_M_ at the last localized pose, kept until a loss (confirmedMapInPlan).
  std::optional<Eigen::Isometry3d> confirmed_B_T_M_;
  std::optional<PoseState> last_state_;  // of the last pose in B
};

// Called after each scan: (scans fed, scans in all, the localizer).
using RunProgress = std::function<void(int done, int total, const slam::Localizer& localizer)>;

// Called after each scan, read or skipped, with the scan when it was read (else null): what a
// run's MCAP file records as the run goes (run/foxglove/live_run_mcap.hpp).
using RunObserver = std::function<void(const sensors::Scan* scan, const slam::Localizer& localizer,
                                       const LocalizerDriver& driver)>;

// The one feed loop of every run, live or replayed: feeds every scan in order through a
// LocalizerDriver (each scan stamped with the stream's stamp) and collects the record. Streams
// hold what a dataset stores (quantiseStreams), so the same streams and scans give the same
// record, bit for bit, whoever produced them.
RunRecord runLocalizer(RunSetup setup, slam::Localizer& localizer, sensors::SensorStreams streams,
                       sensors::ScanSource& scans, const RunProgress& progress = {},
                       const RunObserver& observer = {});

}  // namespace isg::run
