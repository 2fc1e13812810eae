#include "sim/simulation.hpp"

#include "bim/plan_geometry.hpp"
#include "sim/fast_random.hpp"
#include "sim/imu_simulator.hpp"
#include "sim/kidnap_planner.hpp"
#include "sim/odometry_model.hpp"
#include "sim/robot_model.hpp"
#include "sim/route_builder.hpp"
#include "sim/walk_check.hpp"
#include "sim/walk_path.hpp"
#include "worlds/mjcf_generator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace isg::sim {

namespace {

enum Stream : std::uint64_t {
  kRouteStream = 1,
  kOdometryStream = 2,
  kScanStream = 3,
  kImuStream = 4,
  kGaitStream = 5
};
static_assert(kCameraNoiseStream > kGaitStream, "the cameras' stream is a stream of its own");

GaitConfig gaitOf(const bim::RobotConfig& robot, std::mt19937_64 rng) {
  GaitConfig gait;
  gait.frequency_hz = robot.gait.frequency_hz;
  gait.bob_m = robot.gait.bob_m;
  gait.roll_deg = robot.gait.roll_deg;
  gait.pitch_deg = robot.gait.pitch_deg;
  gait.sway_m = robot.gait.sway_m;
  gait.head_turn_deg = robot.gait.head_turn_deg;
  if (robot.carrier == bim::Carrier::kHandheld) {
    gait.handheld = true;
    gait.standing_height = kHandheldHeight;
    gait.turn_rate = kHandheldTurnRate;
    std::uniform_real_distribution<double> phase(0.0, 2.0 * std::numbers::pi);
    for (double& p : gait.head_phases) p = phase(rng);
  }
  return gait;
}

MujocoWorld buildWorld(const bim::Scenario& scenario, const Eigen::Isometry3d& R_T_L) {
  worlds::WorldOptions options;
  // A person carries the handheld sensors: no robot in the world (the walker is not modelled).
  if (scenario.robot.carrier == bim::Carrier::kLegged) options.extra_worldbody = robotMjcf(R_T_L);
  return MujocoWorld::fromXml(worlds::generateMjcf(scenario, options));
}

// A replayed walk as a route: its positions, thinned to kWalkRouteStep apart (a walk of hours
// stays a short list in metadata.json), and the rooms it enters, in the order it first does.
constexpr double kWalkRouteStep = 0.1;  // m
PlannedRoute replayedRoute(const bim::Scenario& scenario, const WalkPath& walk) {
  const bim::Level& level = *scenario.plan.findLevel(scenario.robot.level);
  PlannedRoute route;
  const auto& poses = scenario.robot.route.walk;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const Eigen::Vector2d& p = poses[i].xy;
    if (!route.waypoints.empty() && i + 1 < poses.size() &&
        (p - route.waypoints.back()).norm() < kWalkRouteStep)
      continue;
    route.waypoints.push_back(p);
    route.waypoint_levels.push_back(level.id);
    const std::optional<std::string> room = bim::roomAt(level, p);
    if (room && std::find(route.visited_rooms.begin(), route.visited_rooms.end(), *room) ==
                    route.visited_rooms.end()) {
      route.visited_rooms.push_back(*room);
    }
  }
  route.start_yaw = walk.at(0.0).yaw;
  return route;
}

}  // namespace

Simulation::Simulation(const bim::Scenario& scenario)
    : scenario_(scenario),
      R_T_L_(sensors::mountTransform(scenario.lidar.mount)),
      R_T_I_(sensors::mountTransform(scenario.imu.mount)),
      world_(buildWorld(scenario, R_T_L_)) {
  if (scenario_.lidar.body_occlusion) {
    // A sensor inside the body would see nothing at all.
    const RobotBox body = robotBodyBox();
    const Eigen::Vector3d at = R_T_L_.translation() - body.centre;
    if ((at.cwiseAbs().array() <= body.half.array()).all()) {
      char what[192];
      std::snprintf(what, sizeof what,
                    "the LiDAR sits inside the robot's body (%.2f × %.2f × %.2f m about the "
                    "base's origin): mount it above z = %.2f m or set body_occlusion to false",
                    2 * body.half.x(), 2 * body.half.y(), 2 * body.half.z(),
                    body.centre.z() + body.half.z());
      throw common::InputError(scenario_.source, "/lidar/mount", what);
    }
  }
  grid_ =
      std::make_unique<OccupancyGrid>(scenario_.plan, scenario_.as_built, scenario_.robot.level);
  if (scenario_.robot.route.kind == bim::Route::Kind::kTrajectory) {
    checkWalkClear(scenario_);
    const bim::Route& replayed = scenario_.robot.route;
    const GaitConfig gait = gaitOf(scenario_.robot, generator(kGaitStream));
    auto walk = std::make_shared<const WalkPath>(replayed.walk, replayed.file_orientation,
                                                 gait.turn_rate, replayed.sensor_path);
    route_ = replayedRoute(scenario_, *walk);
    // A sensor's path: the LiDAR is `rig` in the tracked sensor's frame, the base rigid with it.
    const Eigen::Isometry3d S_T_R = sensors::mountTransform(replayed.rig) * R_T_L_.inverse();
    base_motion_ = std::make_unique<BaseMotion>(
        std::move(walk), scenario_.plan.findLevel(scenario_.robot.level)->elevation, gait, S_T_R);
  } else {
    auto rng = generator(kRouteStream);
    route_ = planRoute(scenario_, *grid_, rng);
    // Each waypoint stands on its level's floor; between two levels the base walks a flight.
    const auto waypoints = onTheirFloors(scenario_.plan, route_.waypoints, route_.waypoint_levels);
    base_motion_ = std::make_unique<BaseMotion>(waypoints, route_.start_yaw, scenario_.robot.speed,
                                                gaitOf(scenario_.robot, generator(kGaitStream)));
    planKidnaps(scenario_, *grid_, route_, *base_motion_, rng);
  }
  poseRobot(world_.model(), world_.data(), base_motion_->pose(0.0), 0.0, 0.0);
  lidar_ = makeLidar();
}

std::unique_ptr<LidarSimulator> Simulation::makeLidar() const {
  // The sensor sees the building and its ceilings, never the robot.
  const unsigned building = (1u << worlds::kBuildingGroup) | (1u << worlds::kCeilingGroup);
  return std::make_unique<LidarSimulator>(world_, scenario_.lidar, building);
}

std::mt19937_64 Simulation::generator(std::uint64_t stream, std::uint64_t index) const {
  const std::uint64_t seed = scenario_.seed;
  std::seed_seq sequence{std::uint32_t(seed), std::uint32_t(seed >> 32), std::uint32_t(stream),
                         std::uint32_t(index), std::uint32_t(index >> 32)};
  return std::mt19937_64(sequence);
}

int Simulation::scanCount(double duration) const {
  const double turn = lidar_->turnDuration();
  if (duration < turn) return 0;
  return int(std::floor((duration - turn) / scanPeriod() + 1e-9)) + 1;
}

LidarScan Simulation::scan(int index) { return scan(index, *lidar_); }

LidarScan Simulation::scan(int index, LidarSimulator& lidar) const {
  return scanBlocks(index, lidar, 0, lidar.blockCount());
}

LidarScan Simulation::scanBlocks(int index, LidarSimulator& lidar, int first_block,
                                 int last_block) const {
  return lidar.scanBlocks(
      index * scanPeriod(), [this](double t) { return B_T_L(t); },
      deriveSeed(scenario_.seed, kScanStream, std::uint64_t(index)), first_block, last_block);
}

common::Trajectory Simulation::groundTruth(double duration, double rate_hz) const {
  common::Trajectory out;
  out.reserve(std::size_t(std::max(int(std::floor(duration * rate_hz + 1e-9)) + 1, 0)));
  groundTruth(duration, rate_hz, [&](const common::StampedPose& pose) { out.push_back(pose); });
  return out;
}

void Simulation::groundTruth(double duration, double rate_hz, const PoseSink& each) const {
  const int n = int(std::floor(duration * rate_hz + 1e-9));
  for (int i = 0; i <= n; ++i) {
    const double t = i / rate_hz;
    each({t, base_motion_->pose(t)});
  }
}

std::size_t Simulation::odometryCount(double duration) const {
  if (scenario_.robot.carrier == bim::Carrier::kHandheld) return 0;
  return std::size_t(
      std::max(int(std::floor(duration * scenario_.odometry.rate_hz + 1e-9)) + 1, 0));
}

common::Trajectory Simulation::odometry(double duration) const {
  common::Trajectory out;
  out.reserve(odometryCount(duration));
  odometry(duration, [&](const common::StampedPose& pose) { out.push_back(pose); });
  return out;
}

void Simulation::odometry(double duration, const PoseSink& each) const {
  if (scenario_.robot.carrier == bim::Carrier::kHandheld) return;  // a person has none
  auto rng = generator(kOdometryStream);
  OdometryModel model(scenario_.odometry, base_motion_->pose(0.0));
  const double rate = scenario_.odometry.rate_hz;
  const int n = int(std::floor(duration * rate + 1e-9));
  const std::vector<double> jumps = base_motion_->jumps();
  std::size_t next_jump = 0;
  for (int i = 0; i <= n; ++i) {
    const double t = i / rate;
    // A kidnap since the last tick: the legs moved until the lift, not with it.
    for (; next_jump < jumps.size() && jumps[next_jump] <= t; ++next_jump) {
      model.update(base_motion_->poseBefore(jumps[next_jump]), rng);
      model.teleport(base_motion_->pose(jumps[next_jump]));
    }
    each({t, model.update(base_motion_->pose(t), rng)});
  }
}

std::vector<ImuSample> Simulation::imu(double duration) const {
  return simulateImu(*base_motion_, scenario_.imu, duration,
                     deriveSeed(scenario_.seed, kImuStream, 0));
}

ImuStream Simulation::imuStream(double duration) const {
  return ImuStream(*base_motion_, scenario_.imu, duration,
                   deriveSeed(scenario_.seed, kImuStream, 0));
}

common::Trajectory Simulation::scanPoses(double duration) const {
  common::Trajectory out;
  for (int k = 0; k < scanCount(duration); ++k) {
    const double t = k * scanPeriod() + scanStampOffset();
    out.push_back({t, B_T_L(t)});
  }
  return out;
}

}  // namespace isg::sim
