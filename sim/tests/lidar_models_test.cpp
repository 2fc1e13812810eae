// The LiDAR models (sensors/lidar_model.hpp) as the simulator fires them: every model's table by
// hand (beams, rings, extremes, timing), each model's static scan in a closed room against mj_ray
// (every point where its beam meets the building, at its firing instant and azimuth), its noise on
// the walls, and the scenario's `lidar.model` with its defaults.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <set>

#include "bim/lidar_models.hpp"
#include "bim/scenario.hpp"
#include "common/input_error.hpp"
#include "sensors/lidar_model.hpp"
#include "sensors/vlp16_layout.hpp"
#include "sim/lidar_simulator.hpp"
#include "sim/mujoco_world.hpp"
#include "worlds/mjcf_generator.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

constexpr unsigned kModelGroups = (1u << worlds::kBuildingGroup) | (1u << worlds::kCeilingGroup);

const sensors::LidarModel& model(const char* name) {
  const sensors::LidarModel* m = sensors::findLidarModel(name);
  EXPECT_NE(m, nullptr) << name;
  return *m;
}

TEST(LidarModels, TablesAsTheirSourcesGiveThem) {
  struct Expected {
    const char* name;
    int beams;
    double lowest_deg, highest_deg;
    int sequences_at_10hz, per_packet, per_packet_dual;
    double range_step;
  };
  const Expected expected[] = {
      {"vlp16", 16, -15.0, 15.0, 1808, 24, 12, 0.002},
      {"vlp32c", 32, -25.0, 15.0, 1808, 12, 6, 0.004},
      {"pandar-xt32", 32, -16.0, 15.0, 2000, 8, 4, 0.004},
      {"os0-64", 64, -45.0, 45.0, 1024, 16, 16, 0.001},
      {"os1-64", 64, -16.6, 16.6, 1024, 16, 16, 0.001},
      {"os1-128", 128, -22.5, 22.5, 1024, 16, 16, 0.001},
  };
  ASSERT_EQ(sensors::lidarModels().size(), std::size(expected));
  EXPECT_EQ(sensors::lidarModelList(), "vlp16, vlp32c, pandar-xt32, os0-64, os1-64, os1-128");
  for (const auto& e : expected) {
    const sensors::LidarModel& m = model(e.name);
    ASSERT_EQ(m.lasers(), e.beams) << e.name;
    // Rings number the beams by elevation from 0 = the lowest.
    std::vector<std::pair<int, double>> by_ring;
    for (const auto& b : m.beams) by_ring.push_back({b.ring, b.elevation_deg});
    std::sort(by_ring.begin(), by_ring.end());
    for (int r = 0; r < e.beams; ++r) {
      ASSERT_EQ(by_ring[std::size_t(r)].first, r) << e.name;
      if (r > 0) ASSERT_GT(by_ring[std::size_t(r)].second, by_ring[std::size_t(r) - 1].second);
    }
    EXPECT_NEAR(by_ring.front().second, e.lowest_deg, 1e-9) << e.name;
    EXPECT_NEAR(by_ring.back().second, e.highest_deg, 1e-9) << e.name;
    EXPECT_EQ(m.sequencesPerTurn(10.0), e.sequences_at_10hz) << e.name;
    EXPECT_EQ(m.sequences_per_packet_single, e.per_packet) << e.name;
    EXPECT_EQ(m.sequences_per_packet_dual, e.per_packet_dual) << e.name;
    EXPECT_EQ(m.range_resolution_m, e.range_step) << e.name;
    // Every beam fires within its sequence.
    for (const auto& b : m.beams) {
      EXPECT_GE(b.firing_offset_s, 0.0);
      EXPECT_LT(b.firing_offset_s, m.sequenceDuration(10.0)) << e.name;
    }
    // The scenario's defaults exist under the same name.
    EXPECT_NE(bim::findLidarModelDefaults(e.name), nullptr) << e.name;
  }
  EXPECT_EQ(bim::lidarModelDefaults().size(), std::size(expected));
  // The VLP-16 is the layout the packet decoder shares, laser for laser.
  const sensors::LidarModel& vlp16 = model("vlp16");
  for (int l = 0; l < 16; ++l) {
    EXPECT_EQ(vlp16.beams[std::size_t(l)].elevation_deg,
              sensors::Vlp16Layout::kElevationDeg[std::size_t(l)]);
    EXPECT_EQ(vlp16.beams[std::size_t(l)].ring, sensors::Vlp16Layout::ring(l));
    EXPECT_EQ(vlp16.beams[std::size_t(l)].firing_offset_s,
              sensors::Vlp16Layout::kFiringInterval * l);
  }
  // The VLP-32C fires its lasers in pairs; the XT32's channel 1 fires 0.368 µs into the block and
  // the next ones 1.512 µs apart; an Ouster column fires at once, 1024 columns a turn at any rate.
  EXPECT_EQ(model("vlp32c").beams[5].firing_offset_s, 2.304e-6 * 2);
  EXPECT_NEAR(model("pandar-xt32").beams[31].firing_offset_s, (0.368 + 1.512 * 31) * 1e-6, 1e-15);
  EXPECT_NEAR(model("os1-64").sequenceDuration(20.0), 1.0 / 20480.0, 1e-15);
  EXPECT_EQ(model("os1-64").sequencesPerTurn(20.0), 1024);
  EXPECT_EQ(model("vlp32c").sequencesPerTurn(20.0), 904);
}

// A static scan of each model in D2's closed room, noise off: every point lies where its beam
// (origin, elevation, azimuth offset from the head at its firing instant) meets the building, as
// mj_ray finds it, to the model's range step.
TEST(LidarModels, EveryModelsPointsAreWhereItsBeamsMeetTheBuilding) {
  const auto scenario = worlds::loadScenarioOrBuiltin("builtin:d2", nullptr);
  const MujocoWorld world = MujocoWorld::fromXml(worlds::generateMjcf(scenario));
  const auto mask = groupArray(kModelGroups);
  const Eigen::Vector3d position(3.0, 3.0, 0.71);
  for (const auto& m : sensors::lidarModels()) {
    bim::LidarConfig config;
    config.model = m.name;
    config.range_noise_m = 0.0;
    config.body_occlusion = false;
    config.min_range_m = 0.05;
    LidarSimulator lidar(world, config, kModelGroups);
    const LidarScan scan = lidar.scan(
        0.0,
        [&](double) {
          Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
          T.translation() = position;
          return T;
        },
        1);
    const int sequences = m.sequencesPerTurn(10.0);
    EXPECT_EQ(scan.rays, sequences * m.lasers()) << m.name;
    ASSERT_GT(scan.points.size(), std::size_t(0.9 * scan.rays)) << m.name;  // a closed room
    std::vector<int> beam_of_ring(std::size_t(m.lasers()));
    for (int l = 0; l < m.lasers(); ++l)
      beam_of_ring[std::size_t(m.beams[std::size_t(l)].ring)] = l;
    std::set<int> rings;
    const double period = m.sequenceDuration(10.0);
    for (std::size_t k = 0; k < scan.points.size(); k += 7) {
      const auto& p = scan.points[k];
      rings.insert(p.ring);
      const int l = beam_of_ring[p.ring];
      const sensors::LidarBeam& beam = m.beams[std::size_t(l)];
      // Fired at a whole number of sequences plus its offset.
      const double sequence = (p.time - beam.firing_offset_s) / period;
      ASSERT_NEAR(sequence, std::round(sequence), 1e-3) << m.name;
      const double head = -2.0 * std::numbers::pi * 10.0 * p.time;
      const double radius = m.beam_origin_radius_mm * 1e-3;
      const Eigen::Vector3d origin(radius * std::cos(head), radius * std::sin(head),
                                   beam.vertical_offset_mm * 1e-3);
      const Eigen::Vector3d v = Eigen::Vector3d(p.x, p.y, p.z) - origin;
      const Eigen::Vector3d direction = v.normalized();
      ASSERT_NEAR(std::asin(direction.z()) * 180.0 / std::numbers::pi, beam.elevation_deg, 1e-3)
          << m.name << " ring " << p.ring;
      const double azimuth = std::atan2(direction.y(), direction.x());
      const double expected_azimuth = head + beam.azimuth_offset_deg * std::numbers::pi / 180.0;
      ASSERT_NEAR(std::remainder(azimuth - expected_azimuth, 2.0 * std::numbers::pi), 0.0, 1e-4)
          << m.name;
      const Eigen::Vector3d from = position + origin;
      int geom = -1;
      const double expected = mj_ray(&world.model(), &world.data(), from.data(), direction.data(),
                                     mask.data(), 1, -1, &geom);
      ASSERT_NEAR(v.norm(), expected, 0.5 * m.range_resolution_m + 1e-5) << m.name;
    }
    EXPECT_EQ(int(rings.size()), m.lasers()) << m.name;
  }
}

TEST(LidarModels, AScenariosModelSetsItsDefaultsUnlessTheScenarioSaysOtherwise) {
  const std::string path = ::testing::TempDir() + "lidar_model_scenario.json";
  const auto parse = [&](const std::string& lidar) {
    std::ofstream(path) << R"({"format": "isg.scenario", "version": 1,
      "plan": {"format": "isg.plan", "version": 1, "levels": [{"id": "G", "height": 2.5,
        "walls": [{"id": "A", "start": [0, 0], "end": [5, 0], "thickness": 0.2}]}]},
      "lidar": )" + lidar + "}";
    return bim::loadScenario(path);
  };
  const bim::Scenario plain = parse("{}");
  EXPECT_EQ(plain.lidar.model, "vlp16");
  EXPECT_EQ(plain.lidar.max_range_m, 100.0);
  const bim::Scenario os1 = parse(R"({"model": "os1-64"})");
  EXPECT_EQ(os1.lidar.model, "os1-64");
  EXPECT_EQ(os1.lidar.min_range_m, 0.8);
  EXPECT_EQ(os1.lidar.max_range_m, 120.0);
  EXPECT_EQ(os1.lidar.range_noise_m, 0.015);
  EXPECT_EQ(os1.lidar.detection_range_m, 40.0);
  const bim::Scenario told = parse(R"({"range_noise_m": 0.003, "model": "pandar-xt32"})");
  EXPECT_EQ(told.lidar.range_noise_m, 0.003);
  EXPECT_EQ(told.lidar.max_range_m, 120.0);
  try {
    parse(R"({"model": "hdl64"})");
    ADD_FAILURE() << "an unknown model was read";
  } catch (const common::InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.pointer(), "/lidar/model");
    EXPECT_EQ(e.reason(),
              "unknown LiDAR model \"hdl64\" (known: vlp16, vlp32c, pandar-xt32, os0-64, os1-64, "
              "os1-128)");
  }
}

}  // namespace
}  // namespace isg::sim
