#pragma once

#include <functional>
#include <optional>
#include <string>

#include "eval/tum.hpp"
#include "sim/simulation.hpp"
#include "slam/localizer.hpp"

namespace isg::sim {

// Feeds a localizer as the robot would: for each scan, the odometry up to the end of its turn
// (when the scan is complete), then the scan; and records what the localizer says. The loop and
// the replay of a recorded dataset (`isg slam`) both go through this, so they see the same data
// in the same order and give the same result.
class LocalizerDriver {
 public:
  LocalizerDriver(slam::Localizer& localizer, const eval::Trajectory& odometry, double scan_period)
      : localizer_(localizer), odometry_(odometry), scan_period_(scan_period) {}

  void feed(const slam::Scan& scan);

  // The pose in M after each scan (stamped at the latest odometry), and in B once localized.
  const eval::Trajectory& estimateMap() const { return estimate_map_; }
  const eval::Trajectory& estimate() const { return estimate_; }
  std::optional<double> localizedAt() const { return localized_at_; }

 private:
  slam::Localizer& localizer_;
  const eval::Trajectory& odometry_;
  double scan_period_;
  std::size_t next_odometry_ = 0;
  eval::Trajectory estimate_map_, estimate_;
  std::optional<double> localized_at_;
};

struct LoopOptions {
  double duration = -1.0;  // seconds of robot time; < 0: the whole route
  double groundtruth_rate = 100.0;
  int threads = 2;  // scans are simulated ahead by threads - 1 workers (at least one)
  std::function<void(int done, int total, const slam::Localizer& localizer)> progress;
};

struct LoopResult {
  eval::Trajectory ground_truth;  // B_T_R
  eval::Trajectory odometry;      // M_T_R, as the localizer got it
  eval::Trajectory estimate_map;  // M
  eval::Trajectory estimate;      // B, from the first localized pose on
  std::optional<double> localized_at;
  int scans = 0;
  double sim_seconds = 0.0;
  double wall_seconds = 0.0;
  double realTimeFactor() const { return wall_seconds > 0 ? sim_seconds / wall_seconds : 0.0; }
};

// The simulation in the loop: the world, the walking robot and its sensors feed the localizer
// in-process, in time order. Odometry and scan stamps pass through the dataset's text formats
// first, so that a dataset recorded with the same seed replays to the very same result.
LoopResult runLoop(Simulation& sim, slam::Localizer& localizer, const LoopOptions& options = {});

}  // namespace isg::sim
