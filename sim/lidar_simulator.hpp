#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include "bim/scenario.hpp"
#include "sim/mujoco_world.hpp"
#include "sim/ray_caster.hpp"
#include "sim/scan_caster.hpp"
#include "slam/messages.hpp"

namespace isg::sim {

// One return of the simulated VLP-16: the localizer's own point type (slam/messages.hpp), in the
// LiDAR frame L at its own firing instant (as the real sensor reports it: not deskewed).
using LidarPoint = slam::ScanPoint;

struct LidarScan {
  double stamp = 0.0;  // time of the turn's first firing
  std::vector<LidarPoint> points;
  int rays = 0;
};

// The VLP-16 of docs/simulation.md in a MuJoCo world. Each laser fires from the sensor's pose at
// its own instant, so a scan taken while moving carries real motion distortion.
class LidarSimulator {
 public:
  // `groups`: the geom groups the sensor sees (the building's; never the robot's).
  LidarSimulator(const MujocoWorld& world, const bim::LidarConfig& config, unsigned groups);

  // B_T_L(t) for t in [stamp, stamp + 1/rate]: the sensor pose in the plan frame.
  using PoseAt = std::function<Eigen::Isometry3d(double t)>;

  // One full turn starting at `stamp`. Noise, quantisation and dropout draw from `rng`.
  LidarScan scan(double stamp, const PoseAt& B_T_L, std::mt19937_64& rng);

  double turnDuration() const { return sequences_ * kSequence; }
  int raysPerTurn() const { return sequences_ * 16; }

  // The unit normal of the geom's surface at a point on it (boxes: the face the point lies on).
  Eigen::Vector3d surfaceNormal(int geom, const Eigen::Vector3d& point,
                                const Eigen::Vector3d& direction) const;

 private:
  static constexpr double kSequence = 55.296e-6;
  const MujocoWorld& world_;
  bim::LidarConfig config_;
  RayCaster caster_;
  ScanCaster scan_caster_;
  int sequences_;
  std::vector<float> reflectivity_;  // per geom, from its colour
};

}  // namespace isg::sim
