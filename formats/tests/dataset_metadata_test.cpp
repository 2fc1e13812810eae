// metadata.json's one writer: the dataset's own fields written once, a producer's description
// merged into their sections, every key in the format's order; a description that would write a
// field of the format's own is refused.
#include "formats/dataset_metadata.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace isg::formats::dataset {
namespace {

Metadata recorded() {
  Metadata m;
  m.generator = "isg import 0.1.0";
  m.duration_s = 12.5;
  m.frames = {{"B", "world"}, {"M", "odom"}, {"R", "base_link"}, {"L", "velodyne"}, {"I", "imu"}};
  m.lidar_mount = {0.1, 0.0, 0.5, 0.0, 0.0, 0.0};
  m.R_T_L.translation() = Eigen::Vector3d(0.1, 0.0, 0.5);
  m.lidar = {"recorded", 10.0, 125, "last_packet", 0.1, {-0.1, 0.0}, PcdData::kBinaryCompressed};
  m.imu = Metadata::Imu{200.0, 2500, 0.002, std::nullopt};
  m.imu_mount = Metadata::ImuMount{};
  m.odometry = Metadata::Odometry{50.0};
  return m;
}

std::vector<std::string> keysOf(const nlohmann::ordered_json& object) {
  std::vector<std::string> keys;
  for (const auto& item : object.items()) keys.push_back(item.key());
  return keys;
}

TEST(DatasetMetadata, WritesTheFormatsFieldsOnceInItsOrder) {
  const nlohmann::ordered_json m =
      metadataJson(recorded(), {{"imported_from", {{"file", "walk.bag"}}},
                                {"odometry", {{"topic", "/odom"}}},
                                {"lidar", {{"fields", "x y z intensity ring time"}}}});
  EXPECT_EQ(keysOf(m),
            (std::vector<std::string>{"format", "version", "generator", "duration_s", "frames",
                                      "extrinsics", "lidar", "odometry", "imu", "imported_from"}));
  EXPECT_EQ(m["format"], "isg.dataset");
  EXPECT_EQ(m["version"], 1);
  EXPECT_EQ(keysOf(m["lidar"]),
            (std::vector<std::string>{"model", "rate_hz", "scans", "stamp", "scan_period_s",
                                      "point_time_s", "fields", "pcd_data"}));
  EXPECT_EQ(m["lidar"]["pcd_data"], "binary_compressed");
  EXPECT_EQ(m["lidar"]["point_time_s"], nlohmann::ordered_json::array({-0.1, 0.0}));
  EXPECT_EQ(keysOf(m["frames"]), (std::vector<std::string>{"B", "M", "R", "L", "I"}));
  // The mounts as xyz_rpy and a 4×4 matrix, row by row.
  EXPECT_EQ(m["extrinsics"]["R_T_L"]["xyz_rpy"][2], 0.5);
  EXPECT_EQ(m["extrinsics"]["R_T_L"]["matrix"][2][3], 0.5);
  EXPECT_TRUE(m["extrinsics"].contains("R_T_I"));
  // The IMU's noise where known, and only there.
  EXPECT_EQ(m["imu"]["file"], "imu.csv");
  EXPECT_EQ(m["imu"]["gyroscope_noise_density"], 0.002);
  EXPECT_FALSE(m["imu"].contains("accelerometer_noise_density"));
  EXPECT_EQ(m["odometry"], nlohmann::ordered_json({{"rate_hz", 50.0}, {"topic", "/odom"}}));
}

TEST(DatasetMetadata, NoImuNoOdometryNoSections) {
  Metadata m = recorded();
  m.imu.reset();
  m.imu_mount.reset();
  m.odometry.reset();
  const nlohmann::ordered_json written = metadataJson(m, nlohmann::ordered_json::object());
  EXPECT_FALSE(written.contains("imu"));
  EXPECT_FALSE(written.contains("odometry"));
  EXPECT_FALSE(written["extrinsics"].contains("R_T_I"));
}

TEST(DatasetMetadata, ADescriptionMayNotWriteTheFormatsOwnFields) {
  EXPECT_THROW(metadataJson(recorded(), {{"lidar", {{"scans", 3}}}}), std::logic_error);
  EXPECT_THROW(metadataJson(recorded(), {{"duration_s", 3.0}}), std::logic_error);
  EXPECT_THROW(metadataJson(recorded(), {{"imu", {{"samples", 3}}}}), std::logic_error);
  // A section the dataset does not have is the producer's to write whole.
  Metadata m = recorded();
  m.odometry.reset();
  EXPECT_EQ(metadataJson(m, {{"odometry", {{"note", "none"}}}})["odometry"]["note"], "none");
}

TEST(DatasetMetadata, AnExistingDocumentIsPutInTheFormatsOrder) {
  // As a bag carries an isg dataset's metadata back: keys sorted by name.
  const nlohmann::ordered_json sorted = nlohmann::ordered_json::parse(
      R"({"duration_s": 1, "format": "isg.dataset", "frames": {"I": "i", "B": "b"},
          "lidar": {"pcd_data": "binary", "rate_hz": 10}, "seed": 4, "version": 1, "zeta": 0})");
  const nlohmann::ordered_json ordered = inMetadataOrder(sorted);
  EXPECT_EQ(keysOf(ordered), (std::vector<std::string>{"format", "version", "seed", "duration_s",
                                                       "frames", "lidar", "zeta"}));
  EXPECT_EQ(keysOf(ordered["frames"]), (std::vector<std::string>{"B", "I"}));
  EXPECT_EQ(keysOf(ordered["lidar"]), (std::vector<std::string>{"rate_hz", "pcd_data"}));
  // The same document: only the order changed.
  EXPECT_EQ(nlohmann::json::parse(ordered.dump()), nlohmann::json::parse(sorted.dump()));
}

}  // namespace
}  // namespace isg::formats::dataset
