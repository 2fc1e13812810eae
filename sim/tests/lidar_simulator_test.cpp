#include "sim/lidar_simulator.hpp"

#include <gtest/gtest.h>
#include <numbers>

#include <cmath>
#include <random>
#include <set>

#include "bim/agraph.hpp"
#include "sim/robot_model.hpp"
#include "sim/simulation.hpp"
#include "sim/vlp16.hpp"
#include "worlds/mjcf_generator.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

constexpr unsigned kSimulatorGroups =
    (1u << worlds::kBuildingGroup) | (1u << worlds::kCeilingGroup);

bim::Scenario lidarBuiltin(const std::string& name) {
  return worlds::loadScenarioOrBuiltin("builtin:" + name, nullptr);
}

Eigen::Isometry3d simulatedAt(double x, double y, double z, double yaw = 0.0) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x, y, z);
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return T;
}

TEST(Vlp16, RingsNumberLasersByElevation) {
  std::set<int> rings;
  for (int l = 0; l < Vlp16::kLasers; ++l) {
    rings.insert(Vlp16::ring(l));
    EXPECT_DOUBLE_EQ(Vlp16::kElevationDeg[l], -15.0 + 2.0 * Vlp16::ring(l)) << l;
  }
  EXPECT_EQ(rings.size(), 16u);
  EXPECT_EQ(Vlp16::sequencesPerTurn(10.0), 1808);
  EXPECT_NEAR(Vlp16::firingTime(1, 15), 55.296e-6 + 15 * 2.304e-6, 1e-15);
}

// The incidence every return's intensity, detection and loss are drawn from: the branch-free
// form the rays use against the surface normal's own, bit for bit, on every box of a world whose
// clutter stands turned (upright boxes off the axes) — points on faces, along edges, at corners.
TEST(LidarSimulator, IncidenceIsTheSurfaceNormalsBitForBit) {
  const auto scenario = lidarBuiltin("d1.asbuilt");
  const MujocoWorld world = MujocoWorld::fromXml(worlds::generateMjcf(scenario));
  const LidarSimulator lidar(world, bim::LidarConfig{}, kSimulatorGroups);
  const mjModel& m = world.model();
  const mjData& d = world.data();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> pick(0, 2);
  int boxes = 0, turned = 0, compared = 0;
  for (int g = 0; g < m.ngeom; ++g) {
    if (m.geom_type[g] != mjGEOM_BOX) continue;
    ++boxes;
    const Eigen::Vector3d pos = Eigen::Map<const Eigen::Vector3d>(d.geom_xpos + 3 * g);
    const Eigen::Matrix3d R =
        Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d.geom_xmat + 9 * g);
    const Eigen::Vector3d half = Eigen::Map<const Eigen::Vector3d>(m.geom_size + 3 * g);
    if (std::abs(R(0, 1)) > 1e-6) ++turned;
    for (int k = 0; k < 200; ++k) {
      Eigen::Vector3d local(unit(rng) * half.x(), unit(rng) * half.y(), unit(rng) * half.z());
      // On a face; every 4th on an edge (two coordinates at their faces), every 8th at a corner.
      const int axis = pick(rng);
      local[axis] = (unit(rng) < 0 ? -1 : 1) * half[axis];
      if (k % 4 == 0) local[(axis + 1) % 3] = half[(axis + 1) % 3];
      if (k % 8 == 0) local[(axis + 2) % 3] = -half[(axis + 2) % 3];
      const Eigen::Vector3d point = pos + R * local;
      const Eigen::Vector3d direction =
          Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).normalized();
      const double expected = std::abs(lidar.surfaceNormal(g, point, direction).dot(direction));
      ASSERT_EQ(lidar.cosIncidence(g, point, direction), expected) << g << " " << k;
      ++compared;
    }
  }
  EXPECT_GT(boxes, 20);
  EXPECT_GE(turned, 1);  // the clutter turned by 0.2 rad
  EXPECT_EQ(compared, 200 * boxes);
}

TEST(LidarSimulator, PointsCarryTheirRingElevationAndFiringTime) {
  const auto scenario = lidarBuiltin("d2");
  const MujocoWorld world = MujocoWorld::fromXml(worlds::generateMjcf(scenario));
  bim::LidarConfig config;
  config.range_noise_m = 0.0;
  LidarSimulator lidar(world, config, kSimulatorGroups);
  const std::uint64_t seed = 1;
  const LidarScan scan = lidar.scan(
      0.0, [](double) { return simulatedAt(3, 3, 0.71); }, seed);
  EXPECT_EQ(scan.rays, 1808 * 16);
  ASSERT_GT(scan.points.size(), 25000u);  // a closed room: nearly every ray returns
  for (const auto& p : scan.points) {
    const int laser = Vlp16::laser(p.ring);
    const Eigen::Vector3d v = Eigen::Vector3d(p.x, p.y, p.z) - Vlp16::origin(laser);
    const double elevation = std::asin(v.z() / v.norm()) * 180.0 / std::numbers::pi;
    ASSERT_NEAR(elevation, -15.0 + 2.0 * p.ring, 1e-3);
    // time = 55.296 µs × sequence + 2.304 µs × laser, for a whole number of sequences
    const double sequences = (p.time - laser * Vlp16::kFiringInterval) / Vlp16::kSequenceDuration;
    ASSERT_NEAR(sequences, std::round(sequences), 1e-3);
    ASSERT_GE(p.intensity, 0.0f);
    ASSERT_LE(p.intensity, 255.0f);
  }
}

// RMS distance of points (in B) from the nearest of the room's wall faces, over points within
// 10 cm of the room's footprint (not seen through a doorway), between floor and ceiling, whose
// nearest face is within `gate`.
double wallResidualRms(const std::vector<Eigen::Vector3d>& points, const bim::AGraph& graph,
                       const std::string& room, double gate) {
  const auto& r = graph.rooms[graph.findRoom(room)];
  Eigen::Vector2d lo = r.outline[0], hi = r.outline[0];
  for (const auto& v : r.outline) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  double sum = 0.0;
  int n = 0;
  for (const auto& p : points) {
    if (p.z() < 0.1 || p.z() > 2.9) continue;
    if ((p.head<2>().array() < lo.array() - 0.1).any() ||
        (p.head<2>().array() > hi.array() + 0.1).any()) {
      continue;
    }
    double best = 1e9;
    for (int s : r.surfaces)
      best = std::min(best, std::abs(graph.surfaces[s].plane.signedDistance(p)));
    if (best > gate) continue;
    sum += best * best;
    ++n;
  }
  EXPECT_GT(n, 5000);
  return std::sqrt(sum / n);
}

TEST(LidarSimulator, StaticScanLiesOnTheRoomsWallsWithTheConfiguredNoise) {
  const auto scenario = lidarBuiltin("d2");  // the plan itself: no clutter in the way
  const MujocoWorld world = MujocoWorld::fromXml(worlds::generateMjcf(scenario));
  const bim::AGraph graph = bim::buildAGraph(scenario.plan);
  bim::LidarConfig config;  // 7 mm noise, 2 mm quantum
  LidarSimulator lidar(world, config, kSimulatorGroups);
  const std::uint64_t seed = 2;
  const Eigen::Isometry3d pose = simulatedAt(2.5, 3.0, 0.71, 0.4);
  const LidarScan scan = lidar.scan(
      0.0, [&](double) { return pose; }, seed);
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : scan.points) points.push_back(pose * Eigen::Vector3d(p.x, p.y, p.z));
  const double rms = wallResidualRms(points, graph, "R1", 0.08);
  // σ = 7 mm plus the 2 mm quantum (0.58 mm RMS): about 7.0 mm, within the 6–8 mm of a real
  // VLP-16 on a flat surface.
  EXPECT_NEAR(rms, std::hypot(0.007, 0.002 / std::sqrt(12.0)), 0.001);
  EXPECT_GE(rms, 0.006);
  EXPECT_LE(rms, 0.008);
}

TEST(LidarSimulator, MotionDistortsAScanAndDeskewingRemovesIt) {
  const auto scenario = lidarBuiltin("d2");
  const MujocoWorld world = MujocoWorld::fromXml(worlds::generateMjcf(scenario));
  const bim::AGraph graph = bim::buildAGraph(scenario.plan);
  bim::LidarConfig config;
  config.range_noise_m = 0.002;
  LidarSimulator lidar(world, config, kSimulatorGroups);
  const std::uint64_t seed = 3;
  // Walking at 1.5 m/s while turning at 1 rad/s: 15 cm and 5.7° during one turn.
  auto pose = [](double t) { return simulatedAt(1.8 + 1.5 * t, 2.5, 0.71, 0.2 + 1.0 * t); };
  const LidarScan scan = lidar.scan(0.0, pose, seed);
  std::vector<Eigen::Vector3d> skewed, deskewed;
  for (const auto& p : scan.points) {
    const Eigen::Vector3d q(p.x, p.y, p.z);
    skewed.push_back(pose(scan.stamp) * q);             // all points from the stamp's pose
    deskewed.push_back(pose(scan.stamp + p.time) * q);  // each from its own firing's pose
  }
  // The reference: the same sensor standing still (door jambs and corners add a few millimetres
  // to the 2 mm noise in every case).
  const LidarScan still = lidar.scan(
      0.0, [&](double) { return pose(0.05); }, seed);
  std::vector<Eigen::Vector3d> standing;
  for (const auto& p : still.points)
    standing.push_back(pose(0.05) * Eigen::Vector3d(p.x, p.y, p.z));
  const double rms_still = wallResidualRms(standing, graph, "R1", 0.5);
  const double rms_skewed = wallResidualRms(skewed, graph, "R1", 0.5);
  const double rms_deskewed = wallResidualRms(deskewed, graph, "R1", 0.5);
  EXPECT_LT(rms_still, 0.008);
  EXPECT_GT(rms_skewed, 5.0 * rms_still);
  EXPECT_LT(rms_deskewed, 1.15 * rms_still);
}

TEST(LidarSimulator, RobotNeverSeesItself) {
  Simulation sim(lidarBuiltin("d1.asbuilt"));
  const Eigen::Isometry3d B_T_R = sim.baseMotion().pose(3.0);
  poseRobot(sim.world().model(), sim.world().data(), B_T_R, 0.0, 0.0);
  // The robot is there for rays that look for it: straight down from the sensor onto its back.
  const Eigen::Vector3d sensor = (B_T_R * sim.R_T_L()).translation();
  const auto robot_hit =
      sim.world().ray(sensor, -Eigen::Vector3d::UnitZ(), 1u << worlds::kRobotGroup);
  ASSERT_TRUE(robot_hit);
  EXPECT_EQ(sim.world().geomName(robot_hit->geom).rfind("robot/", 0), 0u);
  // ... but the sensor's scans have no point near it.
  const LidarScan scan = sim.scan(30);
  const RobotBox box = robotBodyBox();
  for (const auto& p : scan.points) {
    const Eigen::Vector3d in_R = sim.R_T_L() * Eigen::Vector3d(p.x, p.y, p.z);
    const bool inside = ((in_R - box.centre).cwiseAbs().array() <= box.half.array() + 0.1).all();
    ASSERT_FALSE(inside) << in_R.transpose();
  }
}

}  // namespace
}  // namespace isg::sim

namespace isg::sim {
namespace {

TEST(LidarSimulator, RangeLimitsAndDropout) {
  const auto scenario = worlds::loadScenarioOrBuiltin("builtin:d2", nullptr);
  const MujocoWorld world = MujocoWorld::fromXml(worlds::generateMjcf(scenario));
  const auto pose = [](double) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(2.0, 3.0, 0.71);
    return T;
  };
  bim::LidarConfig config;
  LidarSimulator all(world, config, kSimulatorGroups);
  const std::uint64_t seed = 4;
  const std::size_t full = all.scan(0.0, pose, seed).points.size();
  config.dropout = 0.5;
  LidarSimulator half(world, config, kSimulatorGroups);
  const double kept = double(half.scan(0.0, pose, seed).points.size()) / full;
  EXPECT_NEAR(kept, 0.5, 0.02);
  config.dropout = 0.0;
  config.min_range_m = 2.0;
  config.max_range_m = 3.0;
  LidarSimulator banded(world, config, kSimulatorGroups);
  const LidarScan scan = banded.scan(0.0, pose, seed);
  ASSERT_FALSE(scan.points.empty());
  for (const auto& p : scan.points) {
    const int laser = Vlp16::laser(p.ring);
    const double range = (Eigen::Vector3d(p.x, p.y, p.z) - Vlp16::origin(laser)).norm();
    ASSERT_GE(range, 2.0 - 1e-4);
    ASSERT_LE(range, 3.0 + 1e-4);
    // Ranges come in 2 mm steps.
    ASSERT_NEAR(range / 0.002, std::round(range / 0.002), 1e-2);
  }
}

}  // namespace
}  // namespace isg::sim
