#include "sim/scan_pipeline.hpp"

#include <algorithm>
#include <cmath>

#include "common/tum.hpp"
#include "formats/dataset_format.hpp"
#include "formats/imu_file.hpp"

namespace isg::sim {

namespace {

// The IMU as imu.csv holds it: through its text, the one definition of its digits; a chunk at a
// time, read back over the samples, so that hours of them never stand as one text or twice.
void throughImuText(std::vector<sensors::ImuSample>& imu) {
  constexpr std::size_t kChunk = 8192;
  for (std::size_t begin = 0; begin < imu.size(); begin += kChunk) {
    const auto first = imu.begin() + std::ptrdiff_t(begin);
    const auto last = imu.begin() + std::ptrdiff_t(std::min(imu.size(), begin + kChunk));
    const auto read = formats::parseImuText(
        formats::dataset::imuText(std::vector<sensors::ImuSample>(first, last)), "imu.csv");
    std::copy(read.begin(), read.end(), first);
  }
}

}  // namespace

sensors::SensorStreams sensorStreams(const Simulation& simulation, double duration,
                                     double groundtruth_rate, ImuDelivery imu_delivery) {
  const double d = duration < 0 ? simulation.duration() : std::min(duration, simulation.duration());
  sensors::SensorStreams streams;
  streams.duration = d;
  // As the dataset's TUM files will hold them (sensors::quantiseStreams), rounded as they come.
  streams.ground_truth.reserve(std::size_t(std::floor(d * groundtruth_rate + 1e-9)) + 1);
  simulation.groundTruth(d, groundtruth_rate, [&](const common::StampedPose& pose) {
    streams.ground_truth.pushQuantised(pose);
  });
  streams.odometry.reserve(simulation.odometryCount(d));
  simulation.odometry(
      d, [&](const common::StampedPose& pose) { streams.odometry.pushQuantised(pose); });
  for (const auto& pose : simulation.scanPoses(d)) {
    streams.scan_stamps.push_back(common::quantisedTime(pose.t));
  }
  streams.scan_period = simulation.scanPeriod();
  streams.R_T_L = simulation.R_T_L();
  if (imu_delivery == ImuDelivery::kWhole) {
    streams.imu = simulation.imu(d);
    throughImuText(streams.imu);
  } else {
    // A minute at a time (12000 samples at 200 Hz): the same samples, never all at once.
    constexpr std::size_t kChunk = 12000;
    auto stream = std::make_shared<ImuStream>(simulation.imuStream(d));
    streams.imu_more = [stream] {
      std::vector<sensors::ImuSample> chunk = stream->next(kChunk);
      throughImuText(chunk);
      return chunk;
    };
    streams.imu = streams.imu_more();
  }
  streams.R_T_I = simulation.R_T_I();
  return streams;
}

LookaheadScans::LookaheadScans(const Simulation& simulation, int scans, int workers, int lookahead)
    : simulation_(simulation),
      scans_(scans),
      workers_(std::max(0, workers)),
      lookahead_(lookahead),
      own_lidar_(simulation.makeLidar()) {
  for (int i = 0; i < workers_; ++i) pool_.emplace_back([this] { work(); });
}

LookaheadScans::~LookaheadScans() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  for (auto& t : pool_) t.join();
}

void LookaheadScans::account(const LidarScan& scan) { timing_ += scan.timing; }

void LookaheadScans::helpWithJob(std::unique_lock<std::mutex>& lock, LidarSimulator& lidar) {
  while (job_ && job_->next_part < job_->parts) {
    const int part = job_->next_part++;
    const int index = job_->index, parts = job_->parts;
    const int blocks = lidar.blockCount();
    lock.unlock();
    std::optional<LidarScan> made;
    std::exception_ptr error;
    try {
      made =
          simulation_.scanBlocks(index, lidar, part * blocks / parts, (part + 1) * blocks / parts);
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    if (error) {
      if (!error_) error_ = error;
      stop_ = true;
    } else {
      account(*made);
      job_->made[part] = std::move(*made);
    }
    ++job_->done;
    changed_.notify_all();
  }
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
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    auto ahead_wanted = [&] {
      next_ahead_ = std::max(next_ahead_, consumed_);
      while (next_ahead_ < scans_ && (ready_.count(next_ahead_) || making_.count(next_ahead_) ||
                                      (job_ && job_->index == next_ahead_)))
        ++next_ahead_;
      return prefetching() && next_ahead_ < std::min(scans_, consumed_ + lookahead_);
    };
    changed_.wait(
        lock, [&] { return stop_ || (job_ && job_->next_part < job_->parts) || ahead_wanted(); });
    if (stop_) return;
    if (job_ && job_->next_part < job_->parts) {
      helpWithJob(lock, *lidar);
      continue;
    }
    const int k = next_ahead_++;
    making_.insert(k);
    lock.unlock();
    std::optional<LidarScan> made;
    std::exception_ptr error;
    try {
      made = simulation_.scan(k, *lidar);
    } catch (...) {
      // The consumer rethrows it on its own thread: a worker's error never ends the process.
      error = std::current_exception();
    }
    lock.lock();
    making_.erase(k);
    if (error) {
      if (!error_) error_ = error;
      stop_ = true;
    } else {
      account(*made);
      ++made_;
      if (k >= consumed_) ready_.emplace(k, std::move(*made));  // else skipped meanwhile
    }
    changed_.notify_all();
  }
}

sensors::Scan LookaheadScans::scan(int index) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (error_) std::rethrow_exception(error_);
  consumed_ = index;  // scans before it are done with; it is index + 1 once this one is taken
  ++streak_;
  ready_.erase(ready_.begin(), ready_.lower_bound(index));  // made ahead, then skipped
  LidarScan scan;
  if (!ready_.count(index) && !making_.count(index)) {
    // Not made ahead: made now, in parts, by this thread and every idle worker.
    job_ = Job{index, workers_ + 1, 0, 0, std::vector<LidarScan>(workers_ + 1)};
    changed_.notify_all();
    helpWithJob(lock, *own_lidar_);
    changed_.wait(lock, [&] { return job_->done == job_->parts || error_; });
    if (error_) std::rethrow_exception(error_);
    scan = std::move(job_->made[0]);
    for (int p = 1; p < job_->parts; ++p) {
      LidarScan& part = job_->made[p];
      scan.points.insert(scan.points.end(), part.points.begin(), part.points.end());
      scan.rays += part.rays;
    }
    job_.reset();
    ++made_;
  } else {
    changed_.wait(lock, [&] { return ready_.count(index) > 0 || error_; });
    if (error_) std::rethrow_exception(error_);
    scan = std::move(ready_[index]);
    ready_.erase(index);
  }
  consumed_ = index + 1;
  changed_.notify_all();
  return {scan.stamp, std::move(scan.points)};
}

void LookaheadScans::skip(int index) {
  std::lock_guard<std::mutex> lock(mutex_);
  consumed_ = index + 1;
  streak_ = 0;
  ready_.erase(ready_.begin(), ready_.upper_bound(index));
  changed_.notify_all();
}

sensors::StageTimes LookaheadScans::stageTimes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  sensors::StageTimes times;
  times.add("poses", timing_.poses_s);
  times.add("casting", timing_.casting_s);
  times.add("noise", timing_.noise_s);
  return times;
}

int LookaheadScans::scansMade() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return made_;
}

}  // namespace isg::sim
