#include "sim/scan_pipeline.hpp"

#include <algorithm>

namespace isg::sim {

run::SensorStreams sensorStreams(const Simulation& simulation, double duration,
                                 double groundtruth_rate) {
  const double d = duration < 0 ? simulation.duration() : std::min(duration, simulation.duration());
  run::SensorStreams streams;
  streams.duration = d;
  streams.ground_truth = simulation.groundTruth(d, groundtruth_rate);
  streams.odometry = simulation.odometry(d);
  for (const auto& pose : simulation.scanPoses(d)) streams.scan_stamps.push_back(pose.t);
  streams.scan_period = simulation.scanPeriod();
  streams.R_T_L = simulation.R_T_L();
  run::quantiseStreams(streams);  // as the dataset's TUM files will hold them
  return streams;
}

LookaheadScans::LookaheadScans(const Simulation& simulation, int scans, int workers, int lookahead)
    : simulation_(simulation), scans_(scans), lookahead_(lookahead) {
  for (int i = 0; i < std::max(1, workers); ++i) pool_.emplace_back([this] { work(); });
}

LookaheadScans::~LookaheadScans() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  for (auto& t : pool_) t.join();
}

void LookaheadScans::work() {
  std::unique_ptr<LidarSimulator> lidar;
  try {
    lidar = simulation_.makeLidar();
  } catch (...) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!error_) error_ = std::current_exception();
    stop_ = true;
    changed_.notify_all();
    return;
  }
  while (true) {
    int k;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(
          lock, [&] { return stop_ || next_to_make_ < std::min(scans_, consumed_ + lookahead_); });
      if (stop_ || next_to_make_ >= scans_) return;
      k = next_to_make_++;
    }
    try {
      LidarScan scan = simulation_.scan(k, *lidar);
      std::lock_guard<std::mutex> lock(mutex_);
      ready_.emplace(k, std::move(scan));
    } catch (...) {
      // The consumer rethrows it on its own thread: a worker's error never ends the process.
      std::lock_guard<std::mutex> lock(mutex_);
      if (!error_) error_ = std::current_exception();
      stop_ = true;
    }
    changed_.notify_all();
  }
}

slam::Scan LookaheadScans::scan(int index) {
  LidarScan scan;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return ready_.count(index) > 0 || error_; });
    if (error_) std::rethrow_exception(error_);
    scan = std::move(ready_[index]);
    ready_.erase(index);
    consumed_ = index + 1;
  }
  changed_.notify_all();
  return {scan.stamp, std::move(scan.points)};
}

}  // namespace isg::sim
