#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <random>
#include <vector>

#include "bim/scenario.hpp"
#include "sensors/messages.hpp"
#include "sim/base_motion.hpp"
#include "sim/fast_random.hpp"

namespace isg::sim {

using sensors::ImuSample;

// What a perfect IMU mounted at R_T_I on the base reads at `t`: the trajectory's exact
// derivatives, the lever arm's centripetal and tangential accelerations included.
ImuSample idealImuSample(const BaseMotion& trajectory, const Eigen::Isometry3d& R_T_I,
                         double gravity, double t);

// The IMU stream of [0, duration] at config.rate_hz (sample i at i / rate), with Kalibr's
// continuous-time noise model discretised at that rate: per axis, white noise of standard
// deviation density / √Δt, plus a bias that starts at zero and steps by random_walk · √Δt · N(0, 1)
// each sample. Every draw comes from `seed`.
std::vector<ImuSample> simulateImu(const BaseMotion& trajectory, const bim::ImuConfig& config,
                                   double duration, std::uint64_t seed);

// The same stream made a chunk at a time, as a run reads it: hours of samples at 200 Hz are
// ~80 MB, and a run needs only the next few. Its chunks, concatenated, are simulateImu's samples
// bit for bit. `trajectory` must outlive it.
class ImuStream {
 public:
  ImuStream(const BaseMotion& trajectory, const bim::ImuConfig& config, double duration,
            std::uint64_t seed);
  // The biases a sample was read with (what EuRoC's ground truth states give).
  struct Bias {
    Eigen::Vector3d gyroscope = Eigen::Vector3d::Zero();
    Eigen::Vector3d accelerometer = Eigen::Vector3d::Zero();
  };
  // The next samples, at most `count`; none once the stream is over. `biases`, when given,
  // receives each sample's biases.
  std::vector<ImuSample> next(std::size_t count, std::vector<Bias>* biases = nullptr);
  std::size_t size() const { return std::size_t(last_) + 1; }  // samples in the whole stream

 private:
  Eigen::Vector3d draw();

  const BaseMotion& trajectory_;
  Eigen::Isometry3d R_T_I_;
  double gravity_, dt_;
  double gyro_white_, accel_white_, gyro_step_, accel_step_;
  int last_, next_ = 0;
  Xoshiro256 rng_;
  std::normal_distribution<double> normal_;  // holds a draw between calls: one for the stream
  Eigen::Vector3d gyro_bias_ = Eigen::Vector3d::Zero(), accel_bias_ = Eigen::Vector3d::Zero();
};

}  // namespace isg::sim
