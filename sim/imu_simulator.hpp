#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "bim/scenario.hpp"
#include "sensors/messages.hpp"
#include "sim/base_motion.hpp"

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

}  // namespace isg::sim
