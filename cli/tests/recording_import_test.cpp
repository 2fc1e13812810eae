// isg import RECORDING.bag: recordings in. Our own bags import back to the dataset they came
// from and replay to the same estimate; bags written by another writer (python3-rosbag, in
// cli/tests/python_recording.py) in the Velodyne driver's and Ouster's conventions import and
// localize; bad recordings get exact errors and leave nothing behind.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "cli/tests/cli_runner.hpp"
#include "formats/pcd_reader.hpp"

namespace isg::cli {
namespace {

namespace fs = std::filesystem;

using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

std::vector<std::vector<double>> numberRows(const std::string& text) {
  std::vector<std::vector<double>> rows;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] == '#' || line[0] == 't') continue;
    for (char& c : line) c = c == ',' ? ' ' : c;
    std::istringstream numbers(line);
    std::vector<double> row;
    for (double v; numbers >> v;) row.push_back(v);
    rows.push_back(row);
  }
  return rows;
}

// The largest difference between two tables of numbers of one shape, over columns [first, last).
double largestDifference(const std::string& a, const std::string& b, std::size_t first,
                         std::size_t last) {
  const auto ra = numberRows(a), rb = numberRows(b);
  EXPECT_EQ(ra.size(), rb.size());
  double out = 0.0;
  for (std::size_t i = 0; i < std::min(ra.size(), rb.size()); ++i) {
    for (std::size_t c = first; c < last && c < ra[i].size(); ++c) {
      out = std::max(out, std::abs(ra[i][c] - rb[i][c]));
    }
  }
  return out;
}

// Each scan's number of points (its PCD's POINTS line), scans 0 … count − 1.
std::vector<long> scanSizes(const testing::Sandbox& sandbox, const std::string& dataset,
                            int count) {
  std::vector<long> sizes;
  for (int i = 0; i < count; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "/scans/%06d.pcd", i);
    const std::string pcd = sandbox.read(dataset + name);
    const std::size_t at = pcd.find("\nPOINTS ");
    sizes.push_back(at == std::string::npos ? -1 : std::stol(pcd.substr(at + 8)));
  }
  return sizes;
}

std::string python(const std::string& arguments) {
  return "/usr/bin/python3 '" + std::string(ISG_SOURCE_DIR) + "/cli/tests/python_recording.py' " +
         arguments;
}

int shell(const testing::Sandbox& sandbox, const std::string& command) {
  return std::system(("cd '" + sandbox.dir().string() + "' && " + command).c_str());
}

double apeRmse(const testing::Sandbox& sandbox, const std::string& run) {
  const auto metrics = nlohmann::json::parse(sandbox.read(run + "/metrics.json"));
  return metrics["ape_B"]["rmse"].get<double>();
}

// The mount `name` (R_T_L, R_T_I) of the dataset ds as --lidar-extrinsic / --imu-extrinsic take it.
std::string mountText(const testing::Sandbox& sandbox, const char* name) {
  const auto metadata = nlohmann::json::parse(sandbox.read("ds/metadata.json"));
  std::string out;
  for (const auto& v : metadata["extrinsics"][name]["xyz_rpy"]) {
    std::ostringstream text;
    text.precision(17);
    text << v.get<double>();
    out += (out.empty() ? "" : ",") + text.str();
  }
  return out;
}

// `imported` (from a recording of the dataset `ds` in builtin:d1) localizes, within 1 cm of APE
// of the dataset's own replay.
void expectLocalizedAsTheOriginal(const testing::Sandbox& sandbox) {
  ASSERT_EQ(sandbox.run("slam ds --plan builtin:d1 -o a -q").exit_code, 0);
  const auto result = sandbox.run("slam imported --plan builtin:d1 -o b");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("localized at t = "));
  EXPECT_LE(apeRmse(sandbox, "b"), 0.05);
  EXPECT_NEAR(apeRmse(sandbox, "b"), apeRmse(sandbox, "a"), 0.01);
}

// simulate → --rosbag → import → slam: the same estimate as replaying the original dataset.
TEST(ImportRecording, OurOwnBagReplaysToTheSameEstimate) {
  testing::Sandbox sandbox("import_round_trip");
  ASSERT_EQ(sandbox.run("simulate builtin:d1 -o ds --duration 20 -q --rosbag ds.bag").exit_code, 0);
  auto result = sandbox.run("import ds.bag -o imported -q");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out,
              StartsWith("isg import: ds.bag -> imported (a bag of an isg dataset: its metadata "
                         "restored)\n  LiDAR         /velodyne_points (sensor_msgs/PointCloud2): "
                         "200 messages\n  IMU           /imu/data (sensor_msgs/Imu): 4001 "
                         "messages\n  odometry      /odom (nav_msgs/Odometry): 1001 messages\n"
                         "  ground truth  /ground_truth (nav_msgs/Odometry): 2001 messages\n"));
  EXPECT_THAT(result.out, HasSubstr("stamped at the start (point times 0.0000 to 0.1000 s"));
  // The streams come back as they were written: scans and IMU byte for byte, poses to the
  // last printed digit of a quaternion that went through a rotation matrix and back.
  EXPECT_EQ(sandbox.read("imported/imu.csv"), sandbox.read("ds/imu.csv"));
  EXPECT_EQ(sandbox.read("imported/scans/000123.pcd"), sandbox.read("ds/scans/000123.pcd"));
  EXPECT_FALSE(sandbox.exists("imported/scans/000200.pcd"));
  EXPECT_EQ(largestDifference(sandbox.read("imported/odometry.tum"),
                              sandbox.read("ds/odometry.tum"), 0, 4),
            0.0);
  EXPECT_LE(largestDifference(sandbox.read("imported/odometry.tum"),
                              sandbox.read("ds/odometry.tum"), 4, 8),
            2e-9);
  EXPECT_EQ(
      largestDifference(sandbox.read("imported/scans.tum"), sandbox.read("ds/scans.tum"), 0, 1),
      0.0);
  auto original = nlohmann::json::parse(sandbox.read("ds/metadata.json"));
  auto imported = nlohmann::json::parse(sandbox.read("imported/metadata.json"));
  EXPECT_EQ(imported["imported_from"]["time_origin_s"], 1000000000);
  imported.erase("imported_from");
  EXPECT_EQ(imported, original);

  ASSERT_EQ(sandbox.run("slam ds --plan builtin:d1 -o a -q").exit_code, 0);
  result = sandbox.run("slam imported --plan builtin:d1 -o b -q");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  // Positions to the printed micrometre, orientations to the last digit.
  EXPECT_EQ(largestDifference(sandbox.read("a/estimate.tum"), sandbox.read("b/estimate.tum"), 0, 4),
            0.0);
  EXPECT_LE(largestDifference(sandbox.read("a/estimate.tum"), sandbox.read("b/estimate.tum"), 4, 8),
            2e-9);
  EXPECT_NEAR(apeRmse(sandbox, "b"), apeRmse(sandbox, "a"), 1e-6);

  // The odometry from the bag's /tf instead (odom → base_link, the same poses): the same file.
  result = sandbox.run("import ds.bag -o fromtf -q --odom-topic /tf");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("  odometry      /tf (tf2_msgs/TFMessage): 1001 messages\n"));
  EXPECT_THAT(result.out,
              HasSubstr("  note: the odometry is the chain odom → base_link (moving) on /tf\n"));
  EXPECT_EQ(sandbox.read("fromtf/odometry.tum"), sandbox.read("imported/odometry.tum"));

  // The same recording without its odometry: the LiDAR and the IMU make it, and the robot is
  // localized as well (docs/slam.md, "Without odometry").
  result = sandbox.run("import ds.bag -o handheld -q --odom-topic none");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("  odometry      none\n"));
  result = sandbox.run("slam handheld --plan builtin:d1 -o c");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("localized at t = "));
  EXPECT_LE(apeRmse(sandbox, "c"), 0.05);
  const auto metrics = nlohmann::json::parse(sandbox.read("c/metrics.json"));
  EXPECT_LE(metrics["map_to_plan"]["rmse"].get<double>(), 0.03);
  EXPECT_GE(metrics["map_to_plan"]["near_share"].get<double>(), 0.95);
}

// The ROS 1 Velodyne driver's conventions (stamped at the end of the turn, PointXYZIRT with its
// padding, NaN points), its mounts on /tf_static, PoseStamped ground truth, bz2 chunks; the
// odometry only as a navigation stack's /tf (odom → base_footprint → base_link, with a
// localizer's map → odom above it and an arm joint beside it), the IMU's mount repeated on /tf.
TEST(ImportRecording, AVelodyneDriverBagFromAnotherWriterLocalizes) {
  testing::Sandbox sandbox("import_velodyne");
  ASSERT_EQ(sandbox.run("simulate builtin:d1 -o ds --duration 20 -q --pcd binary").exit_code, 0);
  ASSERT_EQ(shell(sandbox, python("ds velodyne.bag velodyne --odometry-on-tf")), 0);
  // A frame that is not above the LiDAR cannot be the odometry's: the frames are listed.
  auto result = sandbox.run("import velodyne.bag -o imported -q --odom-frame world");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg import: error: velodyne.bag: the frame \"world\" is not above the LiDAR's frame "
            "on /tf and /tf_static (the frames above the LiDAR's (← on /tf, ⇠ fixed): velodyne ⇠ "
            "base_link ⇠ base_footprint ← odom ← map): name the odometry's frame with "
            "--odom-frame\n");
  EXPECT_FALSE(sandbox.exists("imported"));
  result = sandbox.run("import velodyne.bag -o imported -q");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("  LiDAR         /velodyne_points (sensor_msgs/PointCloud2): "
                                    "200 messages\n"));
  EXPECT_THAT(result.out, HasSubstr("  odometry      /tf (tf2_msgs/TFMessage): 1001 messages\n"));
  EXPECT_THAT(result.out, HasSubstr("  note: the odometry is the chain odom → base_footprint "
                                    "(moving) → base_link (fixed) on /tf\n"));
  EXPECT_THAT(result.out, HasSubstr("  note: /tf repeats transforms that never change, taken as "
                                    "fixed: base_link → imu_link\n"));
  // The odometry as simulated, the chain's fixed link composed back in: stamps to the nanosecond
  // (python's stamps are rounded from seconds), positions to the printed micrometre's rounding,
  // orientations to the last digits.
  const std::string odometry = sandbox.read("imported/odometry.tum");
  EXPECT_LE(largestDifference(odometry, sandbox.read("ds/odometry.tum"), 0, 1), 1.5e-9);
  EXPECT_LE(largestDifference(odometry, sandbox.read("ds/odometry.tum"), 1, 4), 1e-6);
  EXPECT_LE(largestDifference(odometry, sandbox.read("ds/odometry.tum"), 4, 8), 5e-9);
  EXPECT_THAT(result.out,
              HasSubstr("  ground truth  /vicon/base_link (geometry_msgs/PoseStamped): 2001"));
  EXPECT_THAT(result.out,
              HasSubstr("clouds: x y z intensity ring time (the Velodyne driver's layout); "
                        "stamped at the end of the turn (point times -0.1000 to -0.0000 s"));
  const auto metadata = nlohmann::json::parse(sandbox.read("imported/metadata.json"));
  const auto original = nlohmann::json::parse(sandbox.read("ds/metadata.json"));
  EXPECT_EQ(metadata["lidar"]["stamp"], "last_packet");
  EXPECT_NEAR(metadata["lidar"]["point_time_s"][0].get<double>(), -0.1, 1e-3);
  EXPECT_EQ(metadata["frames"]["L"], "velodyne");
  EXPECT_EQ(metadata["frames"]["R"], "base_link");
  // The mounts from /tf_static, as simulated.
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) {
      EXPECT_NEAR(metadata["extrinsics"]["R_T_L"]["matrix"][r][c].get<double>(),
                  original["extrinsics"]["R_T_L"]["matrix"][r][c].get<double>(), 1e-6);
      EXPECT_NEAR(metadata["extrinsics"]["R_T_I"]["matrix"][r][c].get<double>(),
                  original["extrinsics"]["R_T_I"]["matrix"][r][c].get<double>(), 1e-6);
    }
  }
  // Every return kept, the NaN points left out: each scan as simulated.
  EXPECT_EQ(scanSizes(sandbox, "imported", 200), scanSizes(sandbox, "ds", 200));
  EXPECT_EQ(largestDifference(sandbox.read("imported/imu.csv"), sandbox.read("ds/imu.csv"), 1, 7),
            0.0);
  expectLocalizedAsTheOriginal(sandbox);
}

// ouster_ros's layout (t in nanoseconds, uint8 ring, empty pixels as zeros), lz4 chunks, no
// /tf_static: the mounts must be given.
TEST(ImportRecording, AnOusterBagLocalizesWithTheMountsGiven) {
  testing::Sandbox sandbox("import_ouster");
  ASSERT_EQ(sandbox.run("simulate builtin:d1 -o ds --duration 20 -q --pcd binary").exit_code, 0);
  ASSERT_EQ(shell(sandbox, python("ds ouster.bag ouster")), 0);
  auto result = sandbox.run("import ouster.bag -o imported -q");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(
      result.err,
      "isg import: error: ouster.bag: no transform from the base frame \"base_link\" to the "
      "LiDAR's frame \"os_sensor\" in /tf_static: give --lidar-extrinsic X,Y,Z,ROLL,PITCH,YAW "
      "(the LiDAR's pose on the base, metres and radians)\n");
  EXPECT_FALSE(sandbox.exists("imported"));
  const auto mount = [&](const char* name) { return mountText(sandbox, name); };
  result = sandbox.run("import ouster.bag -o imported -q --lidar-extrinsic " + mount("R_T_L") +
                       " --imu-extrinsic " + mount("R_T_I"));
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("clouds: x y z intensity ring t (Ouster's layout); stamped at "
                                    "the start (point times 0.0000 to 0.1000 s"));
  EXPECT_THAT(result.out, HasSubstr("  ground truth  /ground_truth (nav_msgs/Odometry): 2001"));
  // Ouster's empty pixels (zeros) left out: the simulated returns, no more.
  const auto ds = nlohmann::json::parse(sandbox.read("imported/metadata.json"));
  EXPECT_EQ(ds["lidar"]["scans"], 200);
  EXPECT_EQ(scanSizes(sandbox, "imported", 200), scanSizes(sandbox, "ds", 200));
  expectLocalizedAsTheOriginal(sandbox);
}

// isg export --mcap → import: the dataset back, as from the ROS 1 bag.
TEST(ImportRecording, OurOwnMcapImportsBackToTheDataset) {
  testing::Sandbox sandbox("import_mcap_round_trip");
  ASSERT_EQ(sandbox.run("simulate builtin:d1 -o ds --duration 5 -q").exit_code, 0);
  ASSERT_EQ(sandbox.run("export ds --mcap ds.mcap -q").exit_code, 0);
  const auto result = sandbox.run("import ds.mcap -o imported -q");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out,
              StartsWith("isg import: ds.mcap -> imported (a bag of an isg dataset: its metadata "
                         "restored)\n  LiDAR         /velodyne_points "
                         "(sensor_msgs/msg/PointCloud2): 50 messages\n  IMU           /imu/data "
                         "(sensor_msgs/msg/Imu): 1001 messages\n  odometry      /odom "
                         "(nav_msgs/msg/Odometry): 251 messages\n  ground truth  /ground_truth "
                         "(nav_msgs/msg/Odometry): 501 messages\n"));
  EXPECT_EQ(sandbox.read("imported/imu.csv"), sandbox.read("ds/imu.csv"));
  EXPECT_EQ(sandbox.read("imported/scans/000037.pcd"), sandbox.read("ds/scans/000037.pcd"));
  EXPECT_EQ(largestDifference(sandbox.read("imported/odometry.tum"),
                              sandbox.read("ds/odometry.tum"), 0, 4),
            0.0);
  EXPECT_LE(largestDifference(sandbox.read("imported/odometry.tum"),
                              sandbox.read("ds/odometry.tum"), 4, 8),
            2e-9);
  EXPECT_EQ(sandbox.read("imported/scans.tum").substr(0, 200),
            sandbox.read("ds/scans.tum").substr(0, 200));
  auto original = nlohmann::json::parse(sandbox.read("ds/metadata.json"));
  auto imported = nlohmann::json::parse(sandbox.read("imported/metadata.json"));
  imported.erase("imported_from");
  EXPECT_EQ(imported, original);
}

// Scan `k` of two datasets: the same points, rings and intensities, times to the nanosecond.
void expectSameScan(const testing::Sandbox& sandbox, const std::string& a, const std::string& b,
                    int k) {
  char name[32];
  std::snprintf(name, sizeof name, "/scans/%06d.pcd", k);
  const auto pa = formats::readPcd((sandbox.dir() / (a + name)).string());
  const auto pb = formats::readPcd((sandbox.dir() / (b + name)).string());
  ASSERT_EQ(pa.size(), pb.size());
  ASSERT_GT(pa.size(), 1000u);
  for (std::size_t i = 0; i < pa.size(); ++i) {
    ASSERT_EQ(pa[i].x, pb[i].x) << i;
    ASSERT_EQ(pa[i].z, pb[i].z) << i;
    ASSERT_EQ(pa[i].intensity, pb[i].intensity) << i;
    ASSERT_EQ(pa[i].ring, pb[i].ring) << i;
    ASSERT_NEAR(pa[i].time, pb[i].time, 1e-6) << i;
  }
}

// A simulated Ouster's and Hesai's clouds are exported as their ROS drivers publish them (ring 0
// the top beam, Ouster's nanosecond t and range, Hesai's epoch seconds) and import back to the
// dataset, rings renumbered by elevation; --cloud-layout velodyne keeps the Velodyne driver's.
TEST(ImportRecording, AModelsDriverLayoutImportsBackToItsDataset) {
  testing::Sandbox sandbox("import_driver_layouts");
  auto result =
      sandbox.run("simulate builtin:d1 --lidar os1-64 --duration 2 -o os -q --mcap os.mcap");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("isg simulate: clouds in Ouster's (ouster-ros: x y z intensity "
                                    "t reflectivity ring ambient range; ring = beam, 0 = top) "
                                    "layout\n"));
  result = sandbox.run("import os.mcap -o os-back -q");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("clouds: x y z intensity ring t (Ouster's layout)"));
  EXPECT_THAT(result.out,
              HasSubstr("  note: rings renumbered by elevation, 0 = lowest, as datasets "
                        "number them (the recording's ring 0 is the top beam, now "
                        "ring 63)\n"));
  expectSameScan(sandbox, "os", "os-back", 7);
  EXPECT_EQ(nlohmann::json::parse(sandbox.read("os-back/metadata.json"))["lidar"]["scenario_model"],
            "os1-64");

  result = sandbox.run("simulate builtin:d1 --lidar pandar-xt32 --duration 2 -o xt -q");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  result = sandbox.run("export xt --rosbag xt.bag -q");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("isg export: clouds in Hesai's (x y z intensity timestamp "
                                    "ring; ring = channel, 0 = top) layout\n"));
  result = sandbox.run("import xt.bag -o xt-back -q");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("clouds: x y z intensity ring timestamp (Hesai's layout)"));
  EXPECT_THAT(result.out, HasSubstr("(the recording's ring 0 is the top beam, now ring 31)"));
  expectSameScan(sandbox, "xt", "xt-back", 12);

  result = sandbox.run("export xt --rosbag velodyne.bag --cloud-layout velodyne -q");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("isg export: clouds in the Velodyne driver's (x y z intensity "
                                    "ring time; ring 0 = lowest) layout\n"));
  result = sandbox.run("import velodyne.bag -o velodyne-back -q");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, Not(HasSubstr("renumbered")));
  EXPECT_EQ(sandbox.read("velodyne-back/scans/000012.pcd"), sandbox.read("xt/scans/000012.pcd"));
}

std::string pythonRos2(const std::string& arguments) {
  return "/usr/bin/python3 '" + std::string(ISG_SOURCE_DIR) +
         "/cli/tests/python_ros2_recording.py' " + arguments;
}

// A ROS 2 recording in the Hesai driver's conventions from Python's sqlite3, CDR encoded by hand
// (cli/tests/python_ros2_recording.py), with no odometry: the LiDAR and the IMU make it, and the
// rig is localized in the plan. The same recording split in two files with its metadata.yaml, or
// in big-endian CDR, imports to the same dataset.
TEST(ImportRecording, ARos2Db3FromAnotherWriterLocalizesWithoutOdometry) {
  testing::Sandbox sandbox("import_ros2_db3");
  ASSERT_EQ(sandbox.run("simulate builtin:d1 -o ds --duration 20 -q --pcd binary").exit_code, 0);
  ASSERT_EQ(shell(sandbox, pythonRos2("ds hesai.db3")), 0);
  auto result = sandbox.run("import hesai.db3 -o imported -q");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out,
              StartsWith("isg import: hesai.db3 -> imported\n  LiDAR         /hesai/pandar "
                         "(sensor_msgs/msg/PointCloud2): 200 messages\n  IMU           "
                         "/alphasense/imu (sensor_msgs/msg/Imu): 4001 messages\n  odometry      "
                         "none\n  ground truth  /ground_truth (nav_msgs/msg/Odometry): 2001 "
                         "messages\n"));
  EXPECT_THAT(result.out, HasSubstr("clouds: x y z intensity ring timestamp (Hesai's layout); "
                                    "stamped at the start (point times 0.0000 to 0.1000 s"));
  const auto ds = nlohmann::json::parse(sandbox.read("imported/metadata.json"));
  EXPECT_EQ(ds["lidar"]["scans"], 200);
  EXPECT_EQ(scanSizes(sandbox, "imported", 200), scanSizes(sandbox, "ds", 200));
  EXPECT_FALSE(sandbox.exists("imported/odometry.tum"));
  result = sandbox.run("slam imported --plan builtin:d1 -o b");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("localized at t = "));
  EXPECT_LE(apeRmse(sandbox, "b"), 0.05);

  // A cloud shorter than it says: its index on the topic and its row in the database.
  ASSERT_EQ(shell(sandbox, pythonRos2("ds short.db3 --short-cloud 3")), 0);
  result = sandbox.run("import short.db3 -o short -q");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_THAT(result.err, StartsWith("isg import: error: short.db3: topic /hesai/pandar, message 3 "
                                     "(row 106): 1 × "));
  EXPECT_FALSE(sandbox.exists("short"));

  ASSERT_EQ(shell(sandbox, pythonRos2("ds split --split --big-endian")), 0);
  result = sandbox.run("import split -o from_split -q");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  for (const char* file : {"imu.csv", "groundtruth.tum", "scans.tum", "scans/000000.pcd",
                           "scans/000100.pcd", "scans/000199.pcd"}) {
    EXPECT_EQ(sandbox.read(std::string("from_split/") + file),
              sandbox.read(std::string("imported/") + file))
        << file;
  }
}

// The same rig's recording as MCAP from npm's writers (cli/tests/npm_ros2_recording.js: @mcap/core,
// zstd chunks, CDR from @foxglove/rosmsg2-serialization, a JSON channel beside), without
// /tf_static: the mounts are given.
TEST(ImportRecording, AnNpmMcapFromAnotherWriterLocalizesWithoutOdometry) {
  const fs::path modules = fs::path(ISG_SOURCE_DIR) / "ci/oracles/node_modules";
  if (!fs::is_directory(modules / "@mcap/core") || std::system("node --version >/dev/null 2>&1")) {
    GTEST_SKIP() << "node or the npm oracles are not installed (ci/install-deps)";
  }
  testing::Sandbox sandbox("import_ros2_mcap");
  ASSERT_EQ(sandbox.run("simulate builtin:d1 -o ds --duration 20 -q --pcd binary").exit_code, 0);
  ASSERT_EQ(shell(sandbox, "node '" + std::string(ISG_SOURCE_DIR) +
                               "/cli/tests/npm_ros2_recording.js' ds hesai.mcap '" +
                               modules.string() + "'"),
            0);
  auto result = sandbox.run("import hesai.mcap -o imported -q");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg import: error: hesai.mcap: no transform from the base frame \"PandarXT-32\" to "
            "the IMU's frame \"imu_sensor_frame\" in /tf_static: give --imu-extrinsic "
            "X,Y,Z,ROLL,PITCH,YAW (the IMU's pose on the base, metres and radians)\n");
  const auto mount = [&](const char* name) { return mountText(sandbox, name); };
  result =
      sandbox.run("import hesai.mcap -o imported -q --base-frame base_link --lidar-extrinsic " +
                  mount("R_T_L") + " --imu-extrinsic " + mount("R_T_I"));
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("  LiDAR         /hesai/pandar (sensor_msgs/msg/PointCloud2): "
                                    "200 messages\n"));
  EXPECT_THAT(result.out, HasSubstr("  odometry      none\n"));
  EXPECT_EQ(scanSizes(sandbox, "imported", 200), scanSizes(sandbox, "ds", 200));
  result = sandbox.run("slam imported --plan builtin:d1 -o b");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("localized at t = "));
  EXPECT_LE(apeRmse(sandbox, "b"), 0.05);
  // The JSON channel is no ROS message: named when asked for.
  result = sandbox.run("import hesai.mcap -o other -q --imu-topic /diagnostics");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg import: error: hesai.mcap: --imu-topic /diagnostics: the topic carries json "
            "without a schema, the IMU must be sensor_msgs/Imu\n");
  EXPECT_FALSE(sandbox.exists("other"));
}

// The real VLP-16 packet fixture (a ROS 2 bag of velodyne_msgs/msg/VelodyneScan, copied with its
// licence into formats/tests/data/vlp16-real): a short dataset of the turns it holds whole.
TEST(ImportRecording, TheRealVlp16PacketFixtureImportsAsAShortDataset) {
  testing::Sandbox sandbox("import_vlp16_packets");
  const std::string fixture =
      std::string(ISG_SOURCE_DIR) + "/formats/tests/data/vlp16-real/nebula-vlp16-indoor.db3";
  auto result = sandbox.run("import '" + fixture + "' -o real");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("  LiDAR         /velodyne_packets "
                                    "(velodyne_msgs/msg/VelodyneScan): "));
  EXPECT_THAT(result.out, HasSubstr("  IMU           none\n  odometry      none\n"));
  EXPECT_THAT(result.out, HasSubstr("clouds: x y z intensity ring time (VLP-16 packets decoded); "
                                    "stamped at the start"));
  EXPECT_THAT(result.out, HasSubstr("note: 603 VLP-16 packets decoded (dual return) into "));
  const auto ds = nlohmann::json::parse(sandbox.read("real/metadata.json"));
  EXPECT_GE(ds["lidar"]["scans"].get<int>(), 2);
  EXPECT_TRUE(sandbox.exists("real/scans/000001.pcd"));
  EXPECT_TRUE(sandbox.exists("real/scans.txt"));
  // A dataset as any other: isg reads it back (its files checked against its metadata) to export
  // it.
  result = sandbox.run("export real --mcap real.mcap -q");
  EXPECT_EQ(result.exit_code, 0) << result.err;
}

TEST(ImportRecording, BadRecordingsAreExactErrorsAndLeaveNothing) {
  testing::Sandbox sandbox("import_errors");
  ASSERT_EQ(sandbox.run("simulate builtin:d2 -o ds --duration 1 -q --pcd binary").exit_code, 0);
  ASSERT_EQ(shell(sandbox, python("ds two.bag velodyne --extra-cloud-topic --short-cloud 3 "
                                  "--imu-in-g")),
            0);
  // Two clouds: which is the LiDAR is asked, with the candidates.
  auto result = sandbox.run("import two.bag -o imported -q");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg import: error: two.bag: several topics could be the LiDAR: /points_filtered "
            "(sensor_msgs/PointCloud2, 1 message), /velodyne_points (sensor_msgs/PointCloud2, 10 "
            "messages); choose one with --lidar-topic\n");
  // Fixed frames are no odometry; --odom-frame is for odometry on /tf.
  result = sandbox.run(
      "import two.bag -o imported -q --lidar-topic /velodyne_points --odom-topic /tf_static");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg import: error: two.bag: --odom-topic /tf_static: fixed frames do not move; name "
            "the tf topic whose transforms move the base (/tf)\n");
  result =
      sandbox.run("import two.bag -o imported -q --lidar-topic /velodyne_points --odom-frame odom");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg import: error: two.bag: --odom-frame odom: the odometry is /odometry/filtered "
            "(nav_msgs/Odometry); --odom-frame names the odometry's frame on /tf\n");
  result = sandbox.run("import two.bag -o imported -q --lidar-topic /imu/data");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(
      result.err,
      "isg import: error: two.bag: --lidar-topic /imu/data: the topic carries "
      "sensor_msgs/Imu, the LiDAR must be sensor_msgs/PointCloud2 or velodyne_msgs/VelodyneScan\n");
  // A cloud shorter than it says: the topic, its index, the reason.
  result = sandbox.run("import two.bag -o imported -q --lidar-topic /velodyne_points");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_THAT(result.err, StartsWith("isg import: error: two.bag: topic /velodyne_points, message "
                                     "3: 1 × "));
  EXPECT_THAT(result.err, HasSubstr(" points need "));
  EXPECT_FALSE(sandbox.exists("imported"));
  // Up to the short cloud, it imports; the IMU said g, and is converted.
  result = sandbox.run(
      "import two.bag -o imported -q --lidar-topic /velodyne_points --duration "
      "0.3");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("note: the IMU's specific force is in g (median norm 1.0"));
  const std::string imu = sandbox.read("imported/imu.csv");
  const std::size_t lines = std::size_t(std::count(imu.begin(), imu.end(), '\n'));
  std::string original = sandbox.read("ds/imu.csv");
  std::size_t end = 0;
  for (std::size_t i = 0; i < lines; ++i) end = original.find('\n', end) + 1;
  original.resize(end);
  EXPECT_GT(lines, 50u);
  EXPECT_LE(largestDifference(imu, original, 0, 7), 1e-6);
  // Not a bag; no such file; an existing folder.
  sandbox.write("fake.bag", "#ROSBAG V1.2\nsomething");
  result = sandbox.run("import fake.bag -o other -q");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_THAT(result.err, StartsWith("isg import: error: fake.bag: "));
  EXPECT_FALSE(sandbox.exists("other"));
  result = sandbox.run("import two.bag -o imported -q --lidar-topic /velodyne_points");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err,
            "isg import: error: imported: already exists (use --force to replace it)\n");
  // Without odometry the replay makes it from the LiDAR and the IMU, and says so.
  result = sandbox.run(
      "import two.bag -o handheld -q --lidar-topic /velodyne_points --duration "
      "0.3 --odom-topic none");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_FALSE(sandbox.exists("handheld/odometry.tum"));
  result = sandbox.run("slam handheld -o run");
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.err, HasSubstr("isg slam: there is no odometry: the LiDAR and the IMU "
                                    "make it (docs/slam.md, \"Without odometry\")\n"));
}

}  // namespace
}  // namespace isg::cli
