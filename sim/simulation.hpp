#pragma once

#include <Eigen/Geometry>
#include <functional>
#include <memory>
#include <random>
#include <vector>

#include "bim/scenario.hpp"
#include "sensors/mount_transform.hpp"
#include "sensors/sensor_streams.hpp"
#include "sim/base_motion.hpp"
#include "sim/imu_simulator.hpp"
#include "sim/lidar_simulator.hpp"
#include "sim/mujoco_world.hpp"
#include "sim/occupancy_grid.hpp"
#include "sim/route_planner.hpp"

namespace isg::sim {

// One scenario, simulated: the building as built with the robot in it, the planned route, the
// trajectory, the VLP-16 and the odometry. Everything random is drawn from generators derived
// from the scenario's seed and what is being drawn (the route, the odometry, scan k), so any
// scan can be made on its own and the same seed always gives the same data.
// The generator stream of the cameras' noise (Simulation::generator; the others are the
// simulation's own).
inline constexpr std::uint64_t kCameraNoiseStream = 6;

class Simulation {
 public:
  explicit Simulation(const bim::Scenario& scenario);

  const bim::Scenario& scenario() const { return scenario_; }
  const BaseMotion& baseMotion() const { return *base_motion_; }
  const PlannedRoute& route() const { return route_; }
  MujocoWorld& world() { return world_; }
  const MujocoWorld& world() const { return world_; }
  const OccupancyGrid& grid() const { return *grid_; }

  // The time the route takes: the robot stops at its end.
  double duration() const { return base_motion_->duration(); }
  // The LiDAR on the base (scenario lidar.mount).
  const Eigen::Isometry3d& R_T_L() const { return R_T_L_; }
  // Seconds between two clouds (1/rate, or the cloud's packets when cut by packet count).
  double scanPeriod() const { return lidar_->scanPeriod(); }
  // Scan k's first firing is at k × scanPeriod(); its stamp is this much later (the stamp
  // convention: 0, or the start of its last packet).
  double scanStampOffset() const { return lidar_->stampOffset(); }
  // Scans whose whole turn fits in [0, duration].
  int scanCount(double duration) const;
  LidarScan scan(int index);
  // The same scan with a sensor of the caller's (one per thread: a sensor keeps per-turn state).
  LidarScan scan(int index, LidarSimulator& lidar) const;
  // Blocks [first_block, last_block) of scan `index` (LidarSimulator::scanBlocks).
  LidarScan scanBlocks(int index, LidarSimulator& lidar, int first_block, int last_block) const;
  std::unique_ptr<LidarSimulator> makeLidar() const;
  // The sensor the simulation's own scans use (its timing and conventions).
  const LidarSimulator& lidar() const { return *lidar_; }
  Eigen::Isometry3d B_T_L(double t) const { return base_motion_->pose(t) * R_T_L_; }

  common::Trajectory groundTruth(double duration, double rate_hz) const;
  // M_T_R at odometry.rate_hz; none for a handheld carrier.
  common::Trajectory odometry(double duration) const;
  // The same poses handed to `each` in time order, none of them kept (hours of them are held as
  // the caller chooses: sim::sensorStreams rounds them into a common::PoseTrack).
  using PoseSink = std::function<void(const common::StampedPose&)>;
  void groundTruth(double duration, double rate_hz, const PoseSink& each) const;
  void odometry(double duration, const PoseSink& each) const;
  std::size_t odometryCount(double duration) const;     // how many poses odometry(duration) makes
  common::Trajectory scanPoses(double duration) const;  // B_T_L at each scan's stamp
  std::vector<ImuSample> imu(double duration) const;
  ImuStream imuStream(
      double duration) const;  // the same, a chunk at a time    // the IMU stream (scenario imu)
  // The IMU on the base (scenario imu.mount).
  const Eigen::Isometry3d& R_T_I() const { return R_T_I_; }

  std::mt19937_64 generator(std::uint64_t stream, std::uint64_t index = 0) const;

 private:
  bim::Scenario scenario_;
  Eigen::Isometry3d R_T_L_;
  Eigen::Isometry3d R_T_I_;
  MujocoWorld world_;
  std::unique_ptr<OccupancyGrid> grid_;
  PlannedRoute route_;
  std::unique_ptr<BaseMotion> base_motion_;
  std::unique_ptr<LidarSimulator> lidar_;
};

}  // namespace isg::sim
