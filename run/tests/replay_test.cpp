// The replay path on its own: a dataset written through sensors/dataset_format (a box room, scans
// ray-cast by hand, exact odometry), read back by DatasetReader and fed through runLocalizer.
// This executable links isg_run and nothing of MuJoCo, sim or worlds (the test
// ReplayLinksNoMuJoCo checks its link line and ldd).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "common/atomic_folder.hpp"
#include "common/input_error.hpp"
#include "common/tum.hpp"
#include "formats/dataset_format.hpp"
#include "formats/dataset_reader.hpp"
#include "run/builtin_methods.hpp"
#include "run/driver.hpp"
#include "run/evaluate_run.hpp"

namespace isg::run {
namespace {

namespace fs = std::filesystem;

// Distance from `origin` along the unit `direction` to the inside of the box [0, size].
double insideBox(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                 const Eigen::Vector3d& size) {
  double t = 1e9;
  for (int a = 0; a < 3; ++a) {
    if (direction[a] > 1e-12) t = std::min(t, (size[a] - origin[a]) / direction[a]);
    if (direction[a] < -1e-12) t = std::min(t, -origin[a] / direction[a]);
  }
  return t;
}

// A base walking along x through an 8 × 5 × 3 m room at 0.5 m/s; LiDAR 0.5 m above it.
Eigen::Isometry3d B_T_R(double t) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(1.5 + 0.5 * t, 2.0 + 0.2 * std::sin(t), 0.0);
  pose.linear() = Eigen::AngleAxisd(0.1 * std::sin(0.5 * t), Eigen::Vector3d::UnitZ()).matrix();
  return pose;
}

class SyntheticDataset : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("isg_replay_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    const double duration = 6.0, period = 0.1;
    Eigen::Isometry3d R_T_L = Eigen::Isometry3d::Identity();
    R_T_L.translation().z() = 0.5;
    const Eigen::Vector3d room(8, 5, 3);
    common::writeFolderAtomically(
        dir_.string(), common::OutputKind::kDataset, false, [&](const fs::path& tmp) {
          Trajectory truth, odometry, scan_poses;
          for (int i = 0; i <= int(duration * 100); ++i)
            truth.push_back({i / 100.0, B_T_R(i / 100.0)});
          for (int i = 0; i <= int(duration * 50); ++i) {
            odometry.push_back({i / 50.0, B_T_R(0).inverse() * B_T_R(i / 50.0)});
          }
          fs::create_directories(tmp / formats::dataset::kScans);
          for (int k = 0; k * period + period <= duration; ++k) {
            const double stamp = k * period;
            const Eigen::Isometry3d B_T_L = B_T_R(stamp) * R_T_L;  // no motion within a turn
            scan_poses.push_back({stamp, B_T_L});
            std::vector<sensors::ScanPoint> points;
            for (int ring = 0; ring < 16; ++ring) {
              const double elevation = (-15.0 + 2.0 * ring) * std::numbers::pi / 180.0;
              for (int step = 0; step < 900; ++step) {
                const double azimuth = 2.0 * std::numbers::pi * step / 900;
                const Eigen::Vector3d d_L(std::cos(elevation) * std::cos(azimuth),
                                          std::cos(elevation) * std::sin(azimuth),
                                          std::sin(elevation));
                const double range = insideBox(B_T_L.translation(), B_T_L.linear() * d_L, room);
                const Eigen::Vector3d p = range * d_L;
                points.push_back({float(p.x()), float(p.y()), float(p.z()), 100.0f,
                                  std::uint16_t(ring), float(period * step / 900)});
              }
            }
            common::writeFile(tmp / formats::dataset::kScans / formats::dataset::scanFileName(k),
                              formats::dataset::pcdBinary(points));
          }
          common::writeFile(tmp / formats::dataset::kGroundTruth,
                            formats::dataset::trajectoryText(truth));
          common::writeFile(tmp / formats::dataset::kOdometry,
                            formats::dataset::trajectoryText(odometry));
          common::writeFile(tmp / formats::dataset::kScanPoses,
                            formats::dataset::trajectoryText(scan_poses));
          nlohmann::ordered_json metadata = {{"format", formats::dataset::kFormat},
                                             {"version", formats::dataset::kVersion},
                                             {"seed", 5},
                                             {"duration_s", duration},
                                             {"lidar", {{"rate_hz", 1.0 / period}}}};
          metadata["extrinsics"] = formats::dataset::extrinsicsJson({0, 0, 0.5, 0, 0, 0}, R_T_L);
          common::writeFile(tmp / formats::dataset::kMetadata, metadata.dump(2));
        });
  }
  void TearDown() override { fs::remove_all(dir_); }

  RunRecord replay(const std::string& method) {
    formats::DatasetReader dataset(dir_.string());
    sensors::SensorStreams streams = dataset.streams();
    LocalizerContext context;
    context.R_T_L = streams.R_T_L;
    context.start_B_T_M = sensors::trueStartB_T_M(streams);
    const auto localizer = builtinMethods().make(method, context);
    RunSetup setup;
    setup.world = dir_.string();
    setup.method = method;
    return runLocalizer(setup, *localizer, std::move(streams), dataset);
  }

  fs::path dir_;
};

TEST_F(SyntheticDataset, ReaderGivesTheStreamsAsWritten) {
  formats::DatasetReader dataset(dir_.string());
  EXPECT_EQ(dataset.scanCount(), 60);
  EXPECT_DOUBLE_EQ(dataset.scanPeriod(), 0.1);
  const sensors::SensorStreams streams = dataset.streams();
  EXPECT_EQ(streams.ground_truth.size(), 601u);
  EXPECT_EQ(streams.odometry.size(), 301u);
  EXPECT_DOUBLE_EQ(streams.duration, 6.0);
  EXPECT_NEAR(streams.R_T_L.translation().z(), 0.5, 1e-12);
  // The TUM files hold the quantised numbers: quantising again changes nothing.
  sensors::SensorStreams again = streams;
  sensors::quantiseStreams(again);
  EXPECT_EQ(common::toTumText(again.ground_truth.toTrajectory()),
            common::toTumText(streams.ground_truth.toTrajectory()));
  const sensors::Scan scan = dataset.scan(3);
  EXPECT_EQ(scan.points.size(), 16u * 900u);
  EXPECT_EQ(scan.points[901].ring, 1);
  EXPECT_NEAR(scan.points[450].time, 0.05, 1e-6);
  // Start: M is the first odometry pose, placed at the first ground-truth pose.
  EXPECT_TRUE(sensors::trueStartB_T_M(streams).isApprox(B_T_R(0), 1e-6));
}

TEST_F(SyntheticDataset, DeadReckoningOnExactOdometryIsTheGroundTruth) {
  const RunRecord record = replay("dead-reckoning");
  EXPECT_EQ(record.scans, 60);
  ASSERT_TRUE(record.localized_at.has_value());
  EXPECT_EQ(*record.localized_at, 0.1);  // the odometry up to the end of the first turn
  const RunMetrics metrics = evaluateRun(record).metrics;
  ASSERT_TRUE(metrics.ape_B.has_value());
  EXPECT_LT(metrics.ape_B->max, 1e-5);
  EXPECT_EQ(metrics.seed, 0u);  // the setup's, not the dataset's: the command fills it
  EXPECT_DOUBLE_EQ(metrics.sim_seconds, 6.0);
}

TEST_F(SyntheticDataset, SGraphReplayIsDeterministicAndMapsTheRoom) {
  const RunRecord first = replay("s-graph");
  const RunRecord second = replay("s-graph");
  EXPECT_EQ(common::toTumText(first.estimate_map), common::toTumText(second.estimate_map));
  EXPECT_EQ(first.graph.dump(), second.graph.dump());
  EXPECT_TRUE(first.estimate.empty());
  ASSERT_TRUE(first.map.has_value());
  EXPECT_GE(first.map->planes, 4u);  // the four walls
  EXPECT_GE(first.map->keyframes.size(), 3u);
  // Exact odometry and exact scans: the map-frame estimate follows the truth.
  const RunMetrics metrics = evaluateRun(first).metrics;
  ASSERT_TRUE(metrics.ape_M_se3.has_value());
  EXPECT_LT(metrics.ape_M_se3->rmse, 0.02);
}

TEST(DatasetReader, MissingFolderAndBadRateAreNamed) {
  try {
    formats::DatasetReader reader("/nonexistent/dataset");
    FAIL();
  } catch (const common::InputError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/dataset: not a dataset folder (no such directory)");
  }
}

}  // namespace
}  // namespace isg::run
