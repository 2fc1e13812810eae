#pragma once

#include <functional>
#include <optional>

#include "run/run_record.hpp"
#include "run/sensor_streams.hpp"
#include "slam/localizer.hpp"

namespace isg::run {

// Where a run's scans come from: the simulator casting them (sim/), or a recorded dataset
// (DatasetReader). For each k = 0, 1, … in order, either `scan(k)` or `skip(k)` is called once:
// skip when the localizer will not read scan k, so that it need not be made or read at all. The
// scan's stamp is the stream's, so a source only fills the points.
class ScanSource {
 public:
  virtual ~ScanSource() = default;
  virtual slam::Scan scan(int index) = 0;
  virtual void skip(int /*index*/) {}
  // Seconds the source spent by stage (the simulator's poses, casting, noise; a dataset's
  // reading), for the run's stage timing.
  virtual slam::StageTimes stageTimes() const { return {}; }
};

// Feeds a localizer as the robot would: for each scan, the odometry up to the end of its turn
// (when the scan is complete), then the scan; and records what the localizer says.
class LocalizerDriver {
 public:
  LocalizerDriver(slam::Localizer& localizer, const Trajectory& odometry, double scan_period)
      : localizer_(localizer), odometry_(odometry), scan_period_(scan_period) {}

  // Pushes the odometry up to the end of the turn starting at `stamp` and says whether the
  // localizer will read that scan (Localizer::wantsScan). Either feed or skip follows.
  bool wants(double stamp);
  void feed(const slam::Scan& scan);
  // The scan at `stamp` goes unread: the odometry is pushed and the estimate recorded as feed
  // would, without the scan.
  void skip(double stamp);

  // The pose in M after each scan (stamped at the latest odometry), and in B once localized.
  const Trajectory& estimateMap() const { return estimate_map_; }
  const Trajectory& estimate() const { return estimate_; }
  std::optional<double> localizedAt() const { return localized_at_; }

 private:
  void pushOdometryUntil(double t);
  void record();

  slam::Localizer& localizer_;
  const Trajectory& odometry_;
  double scan_period_;
  std::size_t next_odometry_ = 0;
  Trajectory estimate_map_, estimate_;
  std::optional<double> localized_at_;
};

// Called after each scan: (scans fed, scans in all, the localizer).
using RunProgress = std::function<void(int done, int total, const slam::Localizer& localizer)>;

// The one feed loop of every run, live or replayed: feeds every scan in order through a
// LocalizerDriver (each scan stamped with the stream's stamp) and collects the record. Streams
// hold what a dataset stores (quantiseStreams), so the same streams and scans give the same
// record, bit for bit, whoever produced them.
RunRecord runLocalizer(RunSetup setup, slam::Localizer& localizer, SensorStreams streams,
                       ScanSource& scans, const RunProgress& progress = {});

}  // namespace isg::run
