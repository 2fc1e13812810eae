#include "sim/testbed_loop.hpp"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <map>
#include <mutex>
#include <thread>

namespace isg::sim {

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

LoopResult runLoop(Simulation& sim, slam::Localizer& localizer, const LoopOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  LoopResult result;
  const double duration =
      options.duration < 0 ? sim.duration() : std::min(options.duration, sim.duration());
  result.sim_seconds = duration;
  // Through the text formats, as a dataset would carry them.
  result.odometry = eval::parseTum(eval::toTumText(sim.odometry(duration)), "odometry");
  result.ground_truth = eval::parseTum(
      eval::toTumText(sim.groundTruth(duration, options.groundtruth_rate)), "groundtruth");
  const eval::Trajectory stamps = eval::parseTum(eval::toTumText(sim.scanPoses(duration)), "scans");
  const int scans = int(stamps.size());
  result.scans = scans;

  // Workers simulate scans ahead, in any order; the loop consumes them in order.
  const int lookahead = 16;
  std::mutex mutex;
  std::condition_variable changed;
  std::map<int, LidarScan> ready;
  int next_to_make = 0, consumed = 0;
  bool stop = false;
  auto worker = [&] {
    const auto lidar = sim.makeLidar();
    while (true) {
      int k;
      {
        std::unique_lock<std::mutex> lock(mutex);
        changed.wait(lock,
                     [&] { return stop || next_to_make < std::min(scans, consumed + lookahead); });
        if (stop || next_to_make >= scans) return;
        k = next_to_make++;
      }
      LidarScan scan = sim.scan(k, *lidar);
      {
        std::lock_guard<std::mutex> lock(mutex);
        ready.emplace(k, std::move(scan));
      }
      changed.notify_all();
    }
  };
  std::vector<std::thread> pool;
  for (int i = 0; i < std::max(1, options.threads - 1); ++i) pool.emplace_back(worker);
  LocalizerDriver driver(localizer, result.odometry, sim.scanPeriod());
  try {
    for (int k = 0; k < scans; ++k) {
      LidarScan scan;
      {
        std::unique_lock<std::mutex> lock(mutex);
        changed.wait(lock, [&] { return ready.count(k) > 0; });
        scan = std::move(ready[k]);
        ready.erase(k);
        consumed = k + 1;
      }
      changed.notify_all();
      driver.feed({stamps[k].t, std::move(scan.points)});
      if (options.progress) options.progress(k + 1, scans, localizer);
    }
  } catch (...) {
    {
      std::lock_guard<std::mutex> lock(mutex);
      stop = true;
    }
    changed.notify_all();
    for (auto& t : pool) t.join();
    throw;
  }
  {
    std::lock_guard<std::mutex> lock(mutex);
    stop = true;
  }
  changed.notify_all();
  for (auto& t : pool) t.join();
  result.estimate_map = driver.estimateMap();
  result.estimate = driver.estimate();
  result.localized_at = driver.localizedAt();
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace isg::sim
