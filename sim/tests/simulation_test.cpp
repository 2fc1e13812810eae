#include "sim/simulation.hpp"

#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <numbers>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "bim/polygon.hpp"
#include "common/tum.hpp"
#include "sim/dataset_writer.hpp"
#include "sim/odometry_model.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

namespace fs = std::filesystem;

bim::Scenario simulationBuiltin(const std::string& name) {
  return worlds::loadScenarioOrBuiltin("builtin:" + name, nullptr);
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class TourOfEveryReferencePlan : public ::testing::TestWithParam<std::string> {};

TEST_P(TourOfEveryReferencePlan, VisitsEveryRoomKeepingClearOfWallsAndClutter) {
  Simulation sim(simulationBuiltin(GetParam()));
  const auto& rooms = sim.scenario().plan.levels[0].rooms;
  EXPECT_EQ(sim.route().visited_rooms.size(), rooms.size());
  EXPECT_TRUE(sim.route().skipped_rooms.empty());
  // The base's centre, every 5 cm of the way, keeps 0.35 m from walls, clutter and closed doors.
  const BaseMotion& t = sim.baseMotion();
  double least = 1e9;
  for (double s = 0.0; s <= t.duration(); s += 0.1) {
    least = std::min(least, sim.grid().clearanceAt(t.planar(s).xy));
  }
  EXPECT_GE(least, kMinClearance - 1e-6);  // clearances are stored as float
}

INSTANTIATE_TEST_SUITE_P(AsBuilt, TourOfEveryReferencePlan,
                         ::testing::Values("d1.asbuilt", "d2.asbuilt", "d3.asbuilt", "d4.asbuilt",
                                           "d5.asbuilt", "d6.asbuilt"));

TEST(BaseMotion, TurnsOnTheSpotThenWalksWithTheGaitsSway) {
  GaitConfig gait;
  const BaseMotion t({{0, 0}, {2, 0}, {2, 1}}, 0.0, 0.5, 0.0, gait);
  // Each movement starts and stops along raised-cosine ramps of π·rate / (2·acceleration):
  // 0.5236 s at 0.5 m/s and 1.5 m/s², 0.4189 s at 0.8 rad/s and 3 rad/s²; each ramp pair costs
  // one ramp's time over moving at full rate throughout.
  const double walk_ramp = std::numbers::pi * 0.5 / 3.0, turn_ramp = std::numbers::pi * 0.8 / 6.0;
  const double first = 4.0 + walk_ramp, turn = (std::numbers::pi / 2) / 0.8 + turn_ramp;
  EXPECT_NEAR(t.duration(), first + turn + 2.0 + walk_ramp, 1e-9);
  // The ramps are symmetric: halfway in time is halfway along.
  EXPECT_NEAR((t.planar(first / 2).xy - Eigen::Vector2d(1, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(t.planar(first / 2).velocity.x(), 0.5, 1e-12);
  EXPECT_NEAR(t.planar(walk_ramp / 2).acceleration.x(), 1.5, 1e-12);  // the peak, mid-ramp
  EXPECT_NEAR(t.planar(first).velocity.norm(), 0.0, 1e-12);           // stopped at the corner
  const double mid_turn = first + turn / 2;
  EXPECT_NEAR((t.planar(mid_turn).xy - Eigen::Vector2d(2, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(t.planar(mid_turn).yaw, std::numbers::pi / 4, 1e-12);
  EXPECT_NEAR(t.planar(mid_turn).yaw_rate, 0.8, 1e-12);
  // Height bobs by ±1.5 cm around 0.46 m while walking; at rest it stands still.
  double lo = 1e9, hi = -1e9;
  for (double s = 1.0; s < 3.0; s += 0.001) {
    const double z = t.pose(s).translation().z();
    lo = std::min(lo, z);
    hi = std::max(hi, z);
  }
  EXPECT_NEAR(hi, 0.46 + 0.015, 2e-4);
  EXPECT_NEAR(lo, 0.46 - 0.015, 2e-4);
  EXPECT_NEAR(t.pose(t.duration() + 1.0).translation().z(), 0.46, 1e-12);
}

TEST(BaseMotion, AKidnapStartsANewLegAtItsTime) {
  GaitConfig gait;
  const double walk_ramp = std::numbers::pi * 0.5 / 3.0, turn_ramp = std::numbers::pi * 0.8 / 6.0;
  BaseMotion t({{0, 0}, {4, 0}}, 0.0, 0.5, 0.0, gait);  // 8 s (and a ramp) along x
  t.appendLeg(3.0, std::vector<Eigen::Vector3d>{{10, 5, 0}, {10, 7, 0}}, 0.3);  // to (10, 5)
  EXPECT_EQ(t.jumps(), std::vector<double>{3.0});
  // Past its first ramp it has covered half a ramp's time less than at full speed throughout.
  const double x_at_3 = 0.5 * (3.0 - walk_ramp / 2);
  EXPECT_NEAR((t.planar(2.999).xy - Eigen::Vector2d(x_at_3 - 0.0005, 0)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((t.planar(3.0).xy - Eigen::Vector2d(10, 5)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((t.poseBefore(3.0).translation().head<2>() - Eigen::Vector2d(x_at_3, 0)).norm(), 0.0,
              1e-12);
  // It turns from 0.3 rad to face +y (π/2 at 0.8 rad/s), then walks 2 m at 0.5 m/s.
  const double turn = (std::numbers::pi / 2 - 0.3) / 0.8 + turn_ramp;
  EXPECT_NEAR(t.duration(), 3.0 + turn + 4.0 + walk_ramp, 1e-9);
  EXPECT_NEAR(t.arrival(1, 1), t.duration(), 1e-12);
  EXPECT_NEAR((t.planar(t.duration()).xy - Eigen::Vector2d(10, 7)).norm(), 0.0, 1e-12);
}

// D1 as built, kidnapped from its tour halfway into the room farthest from the robot then: the
// ground truth jumps into that room, the odometry goes on as if nothing happened, and the tour
// goes on with the rooms not yet visited.
TEST(Simulation, KidnappedRobotJumpsUnseenByOdometry) {
  bim::Scenario scenario = simulationBuiltin("d1.asbuilt");
  const Simulation plain(scenario);
  const double when = std::round(plain.duration() / 2.0);
  const Eigen::Vector2d then = plain.baseMotion().planar(when).xy;
  const bim::Room* farthest = nullptr;
  for (const auto& room : scenario.plan.levels[0].rooms) {
    if (!farthest || (bim::centroid(room.outline) - then).norm() >
                         (bim::centroid(farthest->outline) - then).norm()) {
      farthest = &room;
    }
  }
  scenario.robot.kidnap.push_back({when, farthest->id, std::nullopt, "L0"});
  const Simulation sim(scenario);
  const auto truth = sim.groundTruth(sim.duration(), 50.0);
  const auto odometry = sim.odometry(sim.duration());
  // Largest step between consecutive rows: the truth's at the kidnap; the odometry's a walk's.
  auto largest_step = [](const common::Trajectory& t, double* at) {
    double largest = 0.0;
    for (std::size_t i = 1; i < t.size(); ++i) {
      const double step = (t[i].pose.translation() - t[i - 1].pose.translation()).norm();
      if (step > largest) largest = step, *at = t[i].t;
    }
    return largest;
  };
  double truth_at = 0.0, odometry_at = 0.0;
  EXPECT_GT(largest_step(truth, &truth_at), 1.0);
  EXPECT_NEAR(truth_at, when, 0.02);
  EXPECT_LT(largest_step(odometry, &odometry_at), 0.05);  // ≤ 0.5 m/s · 0.02 s, plus noise
  EXPECT_TRUE(bim::containsPoint(farthest->outline, sim.baseMotion().planar(when).xy));
  // Every room is reached once the tour resumes.
  std::set<std::string> visited(sim.route().visited_rooms.begin(), sim.route().visited_rooms.end());
  EXPECT_EQ(visited.size(), scenario.plan.levels[0].rooms.size());
}

TEST(Odometry, ErrorGrowsAsTheConfiguredRandomWalk) {
  bim::OdometryConfig config;
  config.translation_noise = 0.02;
  config.heading_noise_deg_per_m = 0.0;
  // 400 robots walk 1 m straight, odometry at 50 Hz: the position error's std is 2 cm.
  double sum2 = 0.0;
  const int runs = 400;
  for (int k = 0; k < runs; ++k) {
    std::mt19937_64 rng(k);
    OdometryModel model(config, Eigen::Isometry3d::Identity());
    Eigen::Isometry3d estimate;
    for (int i = 1; i <= 100; ++i) {
      Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
      truth.translation().x() = i * 0.01;
      estimate = model.update(truth, rng);
    }
    sum2 += (estimate.translation() - Eigen::Vector3d(1, 0, 0)).head<2>().squaredNorm() / 2.0;
  }
  EXPECT_NEAR(std::sqrt(sum2 / runs), 0.02, 0.002);
}

TEST(Dataset, WritesEveryFileAndPclReadsTheScans) {
  const fs::path dir = fs::temp_directory_path() / "isg_dataset_test";
  fs::remove_all(dir);
  Simulation sim(simulationBuiltin("d1.asbuilt"));
  DatasetOptions options;
  options.duration = 2.0;
  const DatasetSummary s = writeDataset(sim, dir.string(), options, nullptr);
  // Turns of 0.09998 s (1808 sequences) starting every 0.1 s that end by 2 s: k = 0 … 19.
  EXPECT_EQ(s.scans, 20);
  for (const char* f :
       {"groundtruth.tum", "odometry.tum", "scans.tum", "imu.csv", "metadata.json"}) {
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  }
  EXPECT_EQ(common::readTum((dir / "groundtruth.tum").string()).size(), 201u);  // 100 Hz
  EXPECT_EQ(common::readTum((dir / "odometry.tum").string()).size(), 101u);     // 50 Hz
  EXPECT_EQ(common::readTum((dir / "scans.tum").string()).size(), 20u);
  // imu.csv: a header line and 401 samples at 200 Hz; at rest at t = 0 it reads +g upwards.
  std::istringstream imu(slurp(dir / "imu.csv"));
  std::string line;
  std::getline(imu, line);
  EXPECT_EQ(line, "t,ax,ay,az,gx,gy,gz");
  std::vector<std::vector<double>> rows;
  while (std::getline(imu, line)) {
    std::vector<double> row;
    std::istringstream fields(line);
    for (std::string field; std::getline(fields, field, ',');) row.push_back(std::stod(field));
    ASSERT_EQ(row.size(), 7u) << line;
    rows.push_back(row);
  }
  ASSERT_EQ(rows.size(), 401u);
  EXPECT_EQ(rows[1][0], 0.005);
  // Within 5 sigma of the white noise (2e-3 m/s²/√Hz and 1.7e-4 rad/s/√Hz at 200 Hz).
  EXPECT_NEAR(rows[0][3], 9.81, 5 * 2e-3 * std::sqrt(200.0));
  EXPECT_NEAR(rows[0][6], 0.0, 5 * 1.7e-4 * std::sqrt(200.0));
  pcl::PCLPointCloud2 cloud;
  ASSERT_EQ(pcl::io::loadPCDFile((dir / "scans" / "000007.pcd").string(), cloud), 0);
  EXPECT_GT(cloud.width, 20000u);
  std::string fields;
  for (const auto& f : cloud.fields) fields += f.name + " ";
  EXPECT_EQ(fields, "x y z intensity ring time ");
  pcl::PointCloud<pcl::PointXYZI> xyzi;
  pcl::fromPCLPointCloud2(cloud, xyzi);
  const LidarScan again = sim.scan(7);
  ASSERT_EQ(xyzi.size(), again.points.size());
  EXPECT_EQ(xyzi[100].x, again.points[100].x);
  EXPECT_EQ(xyzi[100].intensity, again.points[100].intensity);
  // An existing folder is not replaced without --force.
  EXPECT_THROW(writeDataset(sim, dir.string(), options, nullptr), common::InputError);
  fs::remove_all(dir);
}

TEST(Dataset, SameSeedSameBytesOtherSeedOtherBytes) {
  const fs::path root = fs::temp_directory_path() / "isg_determinism_test";
  fs::remove_all(root);
  fs::create_directories(root);
  auto make = [&](const std::string& name, std::uint64_t seed, int threads) {
    bim::Scenario s = simulationBuiltin("d2.asbuilt");
    s.seed = seed;
    Simulation sim(s);
    DatasetOptions options;
    options.duration = 1.5;
    options.threads = threads;
    writeDataset(sim, (root / name).string(), options, nullptr);
  };
  make("a", 11, 1);
  make("b", 11, 2);  // other thread counts: the same bytes
  make("d", 11, 4);
  make("c", 12, 2);
  std::size_t files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(root / "a")) {
    if (!entry.is_regular_file()) continue;
    const fs::path relative = fs::relative(entry.path(), root / "a");
    EXPECT_EQ(slurp(entry.path()), slurp(root / "b" / relative)) << relative;
    EXPECT_EQ(slurp(entry.path()), slurp(root / "d" / relative)) << relative;
    ++files;
  }
  EXPECT_EQ(files, 6u + 15u);  // five files, the output marker and 15 turns ending by 1.5 s
  EXPECT_NE(slurp(root / "a" / "scans" / "000003.pcd"), slurp(root / "c" / "scans" / "000003.pcd"));
  EXPECT_NE(slurp(root / "a" / "odometry.tum"), slurp(root / "c" / "odometry.tum"));
  EXPECT_NE(slurp(root / "a" / "imu.csv"), slurp(root / "c" / "imu.csv"));
  fs::remove_all(root);
}

}  // namespace
}  // namespace isg::sim
