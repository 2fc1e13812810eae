#pragma once

#include <condition_variable>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <thread>
#include <vector>

#include "sensors/scan_source.hpp"
#include "sensors/sensor_streams.hpp"
#include "sim/simulation.hpp"

namespace isg::sim {

// The simulation's sensor streams for a run of `duration` seconds of robot time (< 0: the whole
// route, and never more): ground truth at `groundtruth_rate`, odometry (none for a handheld
// carrier), scan stamps, the LiDAR mount, the IMU and its mount; quantised as a dataset stores them
// (sensors::quantiseStreams), so that a recorded dataset replays to the very same result.
// The IMU whole in `imu`, or made as the run reads it (`imu_more`: the live run, where hours of
// it need not stand in memory); the samples are the same either way.
enum class ImuDelivery { kWhole, kAsTheRunGoes };
sensors::SensorStreams sensorStreams(const Simulation& simulation, double duration,
                                     double groundtruth_rate = 100.0,
                                     ImuDelivery imu_delivery = ImuDelivery::kWhole);

// The live loop's ScanSource: scans made when they are needed, by the calling thread and
// `workers` more (0: the caller alone). Two ways, chosen by what the localizer has been doing:
//  - while it reads every scan (kStreak in a row), the workers make whole scans ahead of it, at
//    most `lookahead` ahead;
//  - while it skips scans (a keyframe every metre, a filter update every 20 cm), nothing is made
//    ahead, where most of it would be thrown away: a scan asked for is split into parts (blocks
//    of firing sequences) made by the caller and the idle workers together.
// Every scan is the same whichever way and by whichever thread it is made (each block draws from
// its own seeded generator), so results do not depend on the number of threads. Worker threads
// stop when the source is destroyed, also on an exception.
class LookaheadScans : public sensors::ScanSource {
 public:
  LookaheadScans(const Simulation& simulation, int scans, int workers, int lookahead = 16);
  ~LookaheadScans() override;
  LookaheadScans(const LookaheadScans&) = delete;
  LookaheadScans& operator=(const LookaheadScans&) = delete;

  sensors::Scan scan(int index) override;
  void skip(int index) override;
  // Seconds spent making scans, by stage (poses, casting, noise), summed over threads; scans made
  // ahead and then skipped included.
  sensors::StageTimes stageTimes() const override;
  int scansMade() const;

  static constexpr int kStreak = 3;

 private:
  // A scan asked for and not made ahead: its parts, taken by whoever is free.
  struct Job {
    int index = -1;
    int parts = 0, next_part = 0, done = 0;
    std::vector<LidarScan> made;
  };
  void work();
  bool prefetching() const { return streak_ >= kStreak; }
  // Makes parts of the current job until none is left; called with `lock` held.
  void helpWithJob(std::unique_lock<std::mutex>& lock, LidarSimulator& lidar);
  void account(const LidarScan& scan);  // with the mutex held

  const Simulation& simulation_;
  const int scans_, workers_, lookahead_;
  std::unique_ptr<LidarSimulator> own_lidar_;  // the calling thread's
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::map<int, LidarScan> ready_;
  std::set<int> making_;  // made ahead, in progress
  std::optional<Job> job_;
  int next_ahead_ = 0, consumed_ = 0, streak_ = 0, made_ = 0;
  ScanTiming timing_;
  bool stop_ = false;
  std::exception_ptr error_;  // the first worker error, rethrown by scan()
  std::vector<std::thread> pool_;
};

}  // namespace isg::sim
