#pragma once

#include <condition_variable>
#include <exception>
#include <map>
#include <mutex>
#include <thread>
#include <vector>

#include "run/driver.hpp"
#include "run/sensor_streams.hpp"
#include "sim/simulation.hpp"

namespace isg::sim {

// The simulation's sensor streams for a run of `duration` seconds of robot time (< 0: the whole
// route, and never more): ground truth at `groundtruth_rate`, odometry, scan stamps, the LiDAR
// mount; quantised as a dataset stores them (run::quantiseStreams), so that a recorded dataset
// replays to the very same result.
run::SensorStreams sensorStreams(const Simulation& simulation, double duration,
                                 double groundtruth_rate = 100.0);

// Scans cast by worker threads ahead of the loop that consumes them in order, at most
// `lookahead` ahead: the live loop's ScanSource. `workers` threads (at least one) each own a
// sensor; every scan is drawn from its own seeded generator, so the result does not depend on
// the number of threads. The threads stop when the source is destroyed, also on an exception.
class LookaheadScans : public run::ScanSource {
 public:
  LookaheadScans(const Simulation& simulation, int scans, int workers, int lookahead = 16);
  ~LookaheadScans() override;
  LookaheadScans(const LookaheadScans&) = delete;
  LookaheadScans& operator=(const LookaheadScans&) = delete;

  slam::Scan scan(int index) override;

 private:
  void work();

  const Simulation& simulation_;
  const int scans_, lookahead_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::map<int, LidarScan> ready_;
  int next_to_make_ = 0, consumed_ = 0;
  bool stop_ = false;
  std::exception_ptr error_;  // the first worker error, rethrown by scan()
  std::vector<std::thread> pool_;
};

}  // namespace isg::sim
