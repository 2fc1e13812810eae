#include "sim/imu_simulator.hpp"

#include <algorithm>
#include <cmath>

#include "sensors/mount_transform.hpp"

namespace isg::sim {

ImuSample idealImuSample(const BaseMotion& trajectory, const Eigen::Isometry3d& R_T_I,
                         double gravity, double t) {
  const BaseKinematics k = trajectory.kinematics(t);
  const Eigen::Matrix3d& B_R_R = k.B_T_R.linear();
  const Eigen::Vector3d& w = k.angular_velocity;
  const Eigen::Vector3d& r = R_T_I.translation();
  // The IMU's origin moves with R's plus the lever arm's rotation (both in R, rotated into B).
  const Eigen::Vector3d acceleration =
      k.acceleration + B_R_R * (k.angular_acceleration.cross(r) + w.cross(w.cross(r)));
  const Eigen::Matrix3d I_R_B = (B_R_R * R_T_I.linear()).transpose();
  ImuSample sample;
  sample.t = t;
  sample.accelerometer = I_R_B * (acceleration + Eigen::Vector3d(0.0, 0.0, gravity));
  sample.gyroscope = R_T_I.linear().transpose() * w;
  return sample;
}

std::vector<ImuSample> simulateImu(const BaseMotion& trajectory, const bim::ImuConfig& config,
                                   double duration, std::uint64_t seed) {
  ImuStream stream(trajectory, config, duration, seed);
  return stream.next(stream.size());
}

ImuStream::ImuStream(const BaseMotion& trajectory, const bim::ImuConfig& config, double duration,
                     std::uint64_t seed)
    : trajectory_(trajectory),
      R_T_I_(sensors::mountTransform(config.mount)),
      gravity_(config.gravity),
      dt_(1.0 / config.rate_hz),
      gyro_white_(config.gyroscope_noise_density / std::sqrt(dt_)),
      accel_white_(config.accelerometer_noise_density / std::sqrt(dt_)),
      gyro_step_(config.gyroscope_random_walk * std::sqrt(dt_)),
      accel_step_(config.accelerometer_random_walk * std::sqrt(dt_)),
      last_(int(std::floor(duration * config.rate_hz + 1e-9))),
      rng_(seed) {}

Eigen::Vector3d ImuStream::draw() {
  Eigen::Vector3d v;  // one draw after another: argument order would be unspecified
  for (int axis = 0; axis < 3; ++axis) v[axis] = normal_(rng_);
  return v;
}

std::vector<ImuSample> ImuStream::next(std::size_t count, std::vector<Bias>* biases) {
  std::vector<ImuSample> samples;
  const int end = int(std::min<std::size_t>(std::size_t(last_ + 1), std::size_t(next_) + count));
  if (end <= next_) return samples;
  samples.reserve(std::size_t(end - next_));
  for (; next_ < end; ++next_) {
    ImuSample s = idealImuSample(trajectory_, R_T_I_, gravity_, next_ * dt_);
    // The draws in a fixed order (gyroscope, accelerometer, then the two bias steps), so the
    // stream depends on the seed alone.
    if (biases) biases->push_back({gyro_bias_, accel_bias_});
    s.gyroscope += gyro_bias_ + gyro_white_ * draw();
    s.accelerometer += accel_bias_ + accel_white_ * draw();
    gyro_bias_ += gyro_step_ * draw();
    accel_bias_ += accel_step_ * draw();
    samples.push_back(s);
  }
  return samples;
}

}  // namespace isg::sim
