// The sensor's and its driver's conventions (docs/simulation.md, "Driver conventions"): where a
// cloud is stamped, where it is cut, the reported azimuth's jitter, and which echoes are reported.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

#include "sim/lidar_simulator.hpp"
#include "sim/simulation.hpp"
#include "sim/tests/body_shadow_by_hand.hpp"
#include "sim/vlp16.hpp"
#include "worlds/mjcf_generator.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

constexpr unsigned kConventionGroups =
    (1u << worlds::kBuildingGroup) | (1u << worlds::kCeilingGroup);
constexpr double kSequence = Vlp16::kSequenceDuration;

Eigen::Isometry3d conventionAt(double x, double y, double z) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

// D2's first room, the sensor standing still in it.
struct Room {
  MujocoWorld world = MujocoWorld::fromXml(
      worlds::generateMjcf(worlds::loadScenarioOrBuiltin("builtin:d2", nullptr)));
  LidarSimulator::PoseAt pose = [](double) { return conventionAt(3, 3, 0.71); };
};

std::pair<float, float> timeSpan(const LidarScan& scan) {
  float lo = 1e9f, hi = -1e9f;
  for (const auto& p : scan.points) {
    lo = std::min(lo, p.time);
    hi = std::max(hi, p.time);
  }
  return {lo, hi};
}

TEST(LidarConventions, ByDefaultACloudIsOneTurnFromAzimuthZeroStampedAtItsFirstFiring) {
  Room room;
  LidarSimulator lidar(room.world, bim::LidarConfig{}, kConventionGroups);
  EXPECT_EQ(lidar.sequencesPerCloud(), 1808);
  EXPECT_DOUBLE_EQ(lidar.scanPeriod(), 0.1);
  EXPECT_EQ(lidar.stampOffset(), 0.0);
  EXPECT_EQ(lidar.startAzimuth(0.3), 0.0);
  const LidarScan scan = lidar.scan(0.3, room.pose, 1);
  EXPECT_EQ(scan.stamp, 0.3);
  const auto [lo, hi] = timeSpan(scan);
  EXPECT_GE(lo, 0.0f);
  EXPECT_NEAR(hi, 1807 * kSequence + 15 * Vlp16::kFiringInterval, 1e-7);
}

TEST(LidarConventions, TheRos1DriversCutAndStampGiveItsTimes) {
  // 76 packets of 24 sequences (ceil(753.6 packets/s / 10 Hz)), stamped at the last packet's
  // start: 75 × 24 sequences after the first firing.
  Room room;
  bim::LidarConfig config;
  config.cut = bim::LidarCut::kPackets;
  LidarSimulator first_firing(room.world, config, kConventionGroups);
  config.stamp = bim::LidarStamp::kLastPacket;
  LidarSimulator last_packet(room.world, config, kConventionGroups);
  EXPECT_EQ(last_packet.sequencesPerCloud(), 1824);
  EXPECT_EQ(last_packet.sequencesPerPacket(), 24);
  EXPECT_DOUBLE_EQ(last_packet.scanPeriod(), 1824 * kSequence);   // 0.10086 s: 9.91 clouds a second
  EXPECT_DOUBLE_EQ(last_packet.stampOffset(), 1800 * kSequence);  // 0.09953 s
  const LidarScan a = first_firing.scan(0.0, room.pose, 3);
  const LidarScan b = last_packet.scan(0.0, room.pose, 3);
  EXPECT_EQ(a.rays, 1824 * 16);
  EXPECT_DOUBLE_EQ(b.stamp, 1800 * kSequence);
  // The real recording's span (docs/simulation.md): −0.0995 … +0.0013 s.
  const auto [lo, hi] = timeSpan(b);
  EXPECT_NEAR(lo, -0.0995328, 1e-6);
  EXPECT_NEAR(hi, 23 * kSequence + 15 * Vlp16::kFiringInterval, 1e-6);  // 0.0013064 s
  // The stamp moves the times and nothing else.
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    ASSERT_EQ(a.points[i].x, b.points[i].x) << i;
    ASSERT_EQ(a.points[i].ring, b.points[i].ring) << i;
    ASSERT_NEAR(a.points[i].time - b.points[i].time, 1800 * kSequence, 1e-7) << i;
  }
  // In dual-return mode a packet holds 12 sequences (each firing fills two data blocks):
  // ceil(1507.2 / 10) = 151 packets, 1812 sequences.
  config.returns = bim::LidarReturns::kDual;
  LidarSimulator dual(room.world, config, kConventionGroups);
  EXPECT_EQ(dual.sequencesPerPacket(), 12);
  EXPECT_EQ(dual.sequencesPerCloud(), 1812);
  EXPECT_DOUBLE_EQ(dual.stampOffset(), 1800 * kSequence);
}

// The azimuth (in L, counter-clockwise) of the earliest return of an upward laser.
double firstAzimuth(const LidarScan& scan) {
  const LidarPoint* first = nullptr;
  for (const auto& p : scan.points) {
    if (p.ring >= 8 && (!first || p.time < first->time)) first = &p;
  }
  return std::atan2(first->y, first->x);
}

TEST(LidarConventions, ACutByPacketsStartsEachCloudWhereTheLastEnded) {
  // The head turns on: 1824 sequences are 363.1°, so each cloud starts 3.1° further round
  // (clockwise: the azimuth decreases).
  Room room;
  bim::LidarConfig config;
  config.cut = bim::LidarCut::kPackets;
  LidarSimulator lidar(room.world, config, kConventionGroups);
  const double period = lidar.scanPeriod();
  const double step = 2 * std::numbers::pi * (10.0 * period - 1.0);
  EXPECT_NEAR(step * 180 / std::numbers::pi, 3.0957, 1e-3);
  for (int k = 0; k < 4; ++k) {
    const double start = k * period;
    EXPECT_NEAR(std::remainder(lidar.startAzimuth(start) + k * step, 2 * std::numbers::pi), 0.0,
                1e-9)
        << k;
    const LidarScan scan = lidar.scan(start, room.pose, 5);
    // The first upward return lies within a sequence's turn (0.2°) after the start azimuth.
    const double behind =
        std::remainder(lidar.startAzimuth(start) - firstAzimuth(scan), 2 * std::numbers::pi);
    EXPECT_GE(behind, -1e-6) << k;
    EXPECT_LT(behind, 0.25 * std::numbers::pi / 180) << k;
  }
  // An angle cut starts every turn at its angle.
  config = bim::LidarConfig{};
  config.cut_angle_deg = 90.0;
  LidarSimulator cut(room.world, config, kConventionGroups);
  for (double start : {0.0, 0.1, 0.7}) {
    EXPECT_DOUBLE_EQ(cut.startAzimuth(start), -std::numbers::pi / 2);
    const double behind = std::remainder(
        -std::numbers::pi / 2 - firstAzimuth(cut.scan(start, room.pose, 2)), 2 * std::numbers::pi);
    EXPECT_GE(behind, -1e-6);
    EXPECT_LT(behind, 0.25 * std::numbers::pi / 180);
  }
}

TEST(LidarConventions, ATurnedCloudStillLosesWhatTheBodyShadows) {
  // The puck on the body: the shadow is worked out anew for a cloud that starts off azimuth 0.
  bim::Scenario scenario = worlds::loadScenarioOrBuiltin("builtin:d1.asbuilt", nullptr);
  scenario.lidar.mount[2] = 0.14;
  scenario.lidar.cut = bim::LidarCut::kPackets;
  Simulation sim(scenario);
  const Eigen::Isometry3d B_T_L = sim.B_T_L(0.0);
  auto lidar = sim.makeLidar();
  const double start = 3 * lidar->scanPeriod();  // 9.3° round
  const double azimuth0 = lidar->startAzimuth(start);
  const LidarScan scan = lidar->scan(
      start, [&](double) { return B_T_L; }, 7);
  std::vector<char> shadow(std::size_t(lidar->sequencesPerCloud()) * Vlp16::kLasers);
  int shadowed = 0;
  for (int s = 0; s < lidar->sequencesPerCloud(); ++s) {
    for (int l = 0; l < Vlp16::kLasers; ++l) {
      const double azimuth = azimuth0 + Vlp16::azimuth(Vlp16::firingTime(s, l), 10.0);
      shadow[s * Vlp16::kLasers + l] = by_hand::blockedByTheTop(sim.R_T_L(), l, azimuth);
      shadowed += shadow[s * Vlp16::kLasers + l];
    }
  }
  EXPECT_GT(shadowed, scan.rays / 10);
  for (const auto& p : scan.points) {
    const int laser = Vlp16::laser(p.ring);
    ASSERT_FALSE(shadow[by_hand::sequenceOf(p.time, laser) * Vlp16::kLasers + laser])
        << "a return through the body, laser " << laser;
  }
  // Returns of each shadowed laser: all but its shadow (the room is closed).
  EXPECT_NEAR(double(scan.points.size()), double(scan.rays - shadowed), 0.01 * scan.rays);
}

TEST(LidarConventions, AzimuthJitterMovesEachDataBlocksReportedAzimuth) {
  Room room;
  bim::LidarConfig config;
  LidarSimulator exact(room.world, config, kConventionGroups);
  config.azimuth_jitter_deg = 0.006;  // a real VLP-16's (docs/simulation.md)
  LidarSimulator jittered(room.world, config, kConventionGroups);
  const LidarScan a = exact.scan(0.0, room.pose, 11);
  const LidarScan b = jittered.scan(0.0, room.pose, 11);
  // The same rays, ranges and noise: only where the points are reported turns.
  ASSERT_EQ(a.points.size(), b.points.size());
  std::map<int, std::vector<double>> by_block;  // data block → reported minus true azimuth
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    const auto& p = a.points[i];
    const auto& q = b.points[i];
    ASSERT_EQ(p.time, q.time);
    ASSERT_NEAR(std::hypot(p.x, p.y), std::hypot(q.x, q.y), 1e-5);
    ASSERT_EQ(p.z, q.z);
    if (std::hypot(p.x, p.y) < 2.0) continue;  // float resolution of the angle
    const int block = by_hand::sequenceOf(p.time, Vlp16::laser(p.ring)) / 2;
    by_block[block].push_back(
        std::remainder(std::atan2(q.y, q.x) - std::atan2(p.y, p.x), 2 * std::numbers::pi));
  }
  // One turn per data block (two sequences), the same for its every point; across blocks a
  // zero-mean spread of the configured size.
  double sum = 0, sum2 = 0;
  for (const auto& [block, turns] : by_block) {
    for (double t : turns) ASSERT_NEAR(t, turns.front(), 2e-6) << block;
    sum += turns.front();
    sum2 += turns.front() * turns.front();
  }
  const double n = double(by_block.size());
  ASSERT_GT(n, 800);
  const double deg = 180 / std::numbers::pi;
  EXPECT_NEAR(sum / n * deg, 0.0, 0.001);
  EXPECT_NEAR(std::sqrt(sum2 / n) * deg, 0.006, 0.0006);
}

// A wall's end 3 m ahead, 10° right of the sensor's x axis, in front of a wall 8 m away.
MujocoWorld wallEndBeforeAWall() {
  const double edge_y = -3.0 * std::tan(10.0 * std::numbers::pi / 180);
  char xml[1024];
  std::snprintf(xml, sizeof xml,
                "<mujoco><asset><material name=\"wall\"/></asset><worldbody>"
                "<geom type=\"box\" size=\"0.05 1 2\" pos=\"3.05 %.6f 0\" group=\"%d\" "
                "material=\"wall\"/>"
                "<geom type=\"box\" size=\"0.05 6 2\" pos=\"8.05 0 0\" group=\"%d\" "
                "material=\"wall\"/></worldbody></mujoco>",
                edge_y - 1.0, worlds::kBuildingGroup, worlds::kBuildingGroup);
  return MujocoWorld::fromXml(xml);
}

double rangeOf(const LidarPoint& p) {
  return (Eigen::Vector3d(p.x, p.y, p.z) - Vlp16::origin(Vlp16::laser(p.ring))).norm();
}

TEST(LidarConventions, ABeamAcrossAWallsEndHasTwoEchoes) {
  const MujocoWorld world = wallEndBeforeAWall();
  const auto pose = [](double) { return conventionAt(0, 0, 0); };
  bim::LidarConfig config;
  config.range_noise_m = 0.0;
  config.returns = bim::LidarReturns::kDual;
  LidarSimulator dual(world, config, kConventionGroups);
  config.returns = bim::LidarReturns::kLast;
  LidarSimulator last(world, config, kConventionGroups);
  config.returns = bim::LidarReturns::kStrongest;
  LidarSimulator strongest(world, config, kConventionGroups);
  const LidarScan d = dual.scan(0.0, pose, 9);
  const LidarScan l = last.scan(0.0, pose, 9);
  const LidarScan s = strongest.scan(0.0, pose, 9);
  // Firings with two points in dual mode: the beam straddles the edge (3 mrad wide: 9 mm at 3 m),
  // so one echo comes from the near wall and one from the far one.
  std::map<std::pair<int, float>, std::vector<const LidarPoint*>> firings;
  for (const auto& p : d.points) firings[{p.ring, p.time}].push_back(&p);
  int pairs = 0;
  for (const auto& [firing, points] : firings) {
    ASSERT_LE(points.size(), 2u);
    if (points.size() < 2) continue;
    ++pairs;
    // The last echo first, then the strongest (or second strongest).
    EXPECT_NEAR(points[0]->x, 8.0, 0.01);
    // The near wall's face or its end (0.1 m thick) that the beam's edge grazes.
    EXPECT_GT(points[1]->x, 2.99);
    EXPECT_LT(points[1]->x, 3.11);
    EXPECT_LT(rangeOf(*points[1]), rangeOf(*points[0]) - 1.0);
    // Part of a beam lights part of the intensity.
    EXPECT_LT(points[0]->intensity + points[1]->intensity, 51.0f);
  }
  // At most one straddling firing per laser and edge crossing; most lasers have one.
  EXPECT_GE(pairs, 8);
  EXPECT_LE(pairs, 32);
  // Last mode reports exactly the dual mode's last echoes (same draws), one per firing.
  std::size_t matched = 0;
  std::map<std::pair<int, float>, const LidarPoint*> last_by_firing;
  for (const auto& p : l.points) {
    ASSERT_TRUE(last_by_firing.emplace(std::make_pair(int(p.ring), p.time), &p).second);
  }
  for (const auto& [firing, points] : firings) {
    const auto it = last_by_firing.find(firing);
    ASSERT_NE(it, last_by_firing.end());
    EXPECT_EQ(it->second->x, points[0]->x);
    ++matched;
  }
  EXPECT_EQ(matched, l.points.size());
  EXPECT_EQ(d.points.size(), l.points.size() + pairs);
  // Away from the edge all three modes see the same wall: as many returns within 1 %.
  EXPECT_NEAR(double(s.points.size()), double(l.points.size()), 0.01 * s.points.size());
}

}  // namespace
}  // namespace isg::sim
