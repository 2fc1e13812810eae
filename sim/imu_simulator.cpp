#include "sim/imu_simulator.hpp"

#include <cmath>
#include <random>

#include "sensors/mount_transform.hpp"
#include "sim/fast_random.hpp"

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
  const Eigen::Isometry3d R_T_I = sensors::mountTransform(config.mount);
  const double dt = 1.0 / config.rate_hz;
  const int n = int(std::floor(duration * config.rate_hz + 1e-9));
  const double gyro_white = config.gyroscope_noise_density / std::sqrt(dt);
  const double accel_white = config.accelerometer_noise_density / std::sqrt(dt);
  const double gyro_step = config.gyroscope_random_walk * std::sqrt(dt);
  const double accel_step = config.accelerometer_random_walk * std::sqrt(dt);
  Xoshiro256 rng(seed);
  std::normal_distribution<double> normal;
  auto draw = [&] {
    Eigen::Vector3d v;  // one draw after another: argument order would be unspecified
    for (int axis = 0; axis < 3; ++axis) v[axis] = normal(rng);
    return v;
  };
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero(), accel_bias = Eigen::Vector3d::Zero();
  std::vector<ImuSample> samples;
  samples.reserve(std::size_t(n) + 1);
  for (int i = 0; i <= n; ++i) {
    ImuSample s = idealImuSample(trajectory, R_T_I, config.gravity, i * dt);
    // The draws in a fixed order (gyroscope, accelerometer, then the two bias steps), so the
    // stream depends on the seed alone.
    s.gyroscope += gyro_bias + gyro_white * draw();
    s.accelerometer += accel_bias + accel_white * draw();
    gyro_bias += gyro_step * draw();
    accel_bias += accel_step * draw();
    samples.push_back(s);
  }
  return samples;
}

}  // namespace isg::sim
