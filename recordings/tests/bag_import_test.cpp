// The import of a ROS 1 recording on its own (recordings/bag_import): a bag written here with the
// project's writer and Debian's message serialisers — a LiDAR on a base that drives along x, its
// odometry, an IMU at rest, the mounts on /tf_static — becomes a dataset whose every number is
// known by hand. The whole command (topics chosen, Python-written bags, Ouster layouts) is
// cli/tests/recording_import_test.cpp's.
#include "recordings/bag_import.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "common/input_error.hpp"
#include "common/tum.hpp"
#include "formats/dataset_format.hpp"
#include "formats/imu_file.hpp"
#include "formats/pcd_reader.hpp"
#include "formats/ros2_bag.hpp"
#include "formats/ros2_message_decode.hpp"
#include "formats/ros_messages.hpp"
#include "formats/rosbag_writer.hpp"
#include "formats/tests/scratch_files.hpp"
#include "sensors/mount_transform.hpp"

namespace isg::recordings {
namespace {

namespace fs = std::filesystem;

// What the recording holds; each field changes one thing from a clean bag.
struct Recording {
  int clouds = 10;  // at 10 Hz from t = 100 s
  std::string cloud_frame = "velodyne";
  int odd_frame_cloud = -1;  // this cloud in another frame
  double gravity = 9.81;     // the IMU's reading at rest (1.0: a driver in g)
  // More /tf_static links (parent, child), after the mounts.
  std::vector<std::pair<std::string, std::string>> more_static;
  bool odometry_on_tf = false;  // odom → base_link on /tf instead of /odom
  bool tf_back_link = false;    // and base_link → odom moving on /tf too: a cycle
};

Eigen::Isometry3d baseAt(double t) {
  Eigen::Isometry3d M_T_R = Eigen::Isometry3d::Identity();
  M_T_R.translation().x() = 0.5 * (t - 100.0);  // 0.5 m/s along x
  return M_T_R;
}

std::string writeBag(const fs::path& dir, const Recording& r) {
  const std::string path = (dir / "walk.bag").string();
  formats::RosbagWriter bag(path, true);
  const int tf_static = bag.connect("/tf_static", formats::ros1::tfMessageType(), true);
  const int cloud = bag.connect("/velodyne_points", formats::ros1::pointCloud2Type());
  const int odom = r.odometry_on_tf ? bag.connect("/tf", formats::ros1::tfMessageType())
                                    : bag.connect("/odom", formats::ros1::odometryType());
  const int imu = bag.connect("/imu/data", formats::ros1::imuType());
  auto at = [](double t) { return formats::RosTime::fromSeconds(t); };
  bag.write(tf_static, at(100.0),
            formats::ros1::tfMessage({{at(100.0), "base_link", "velodyne",
                                       sensors::mountTransform({0, 0, 0.5, 0, 0, 0})},
                                      {at(100.0), "base_link", "imu_link",
                                       sensors::mountTransform({-0.1, 0, 0.2, 0, 0, 0})}}));
  for (const auto& [parent, child] : r.more_static) {
    bag.write(tf_static, at(100.0),
              formats::ros1::tfMessage(
                  {{at(100.0), parent, child, sensors::mountTransform({0, 0, -0.5, 0, 0, 0})}}));
  }
  // Odometry at 50 Hz and the IMU at 100 Hz over the clouds' span and a little beyond.
  const double end = 100.0 + 0.1 * r.clouds + 0.1;
  for (int k = 0; 100.0 + 0.02 * k <= end; ++k) {
    const double t = 100.0 + 0.02 * k;
    if (r.odometry_on_tf) {
      std::vector<formats::ros1::StampedTransform> moving = {
          {at(t), "odom", "base_link", baseAt(t)}};
      if (r.tf_back_link) moving.push_back({at(t), "base_link", "odom", baseAt(t).inverse()});
      bag.write(odom, at(t), formats::ros1::tfMessage(moving));
      continue;
    }
    bag.write(
        odom, at(t),
        formats::ros1::odometry(baseAt(t), {0.5, 0, 0}, {0, 0, 0}, at(t), k, "odom", "base_link"));
  }
  for (int k = 0; 100.0 + 0.01 * k <= end; ++k) {
    const double t = 100.0 + 0.01 * k;
    sensors::ImuSample sample;
    sample.accelerometer = Eigen::Vector3d(0, 0, r.gravity);
    bag.write(imu, at(t), formats::ros1::imu(sample, at(t), k, "imu_link", 1e-6, 1e-4));
  }
  // Clouds stamped at the end of their turn: the points' times run from −0.1 to 0 s.
  for (int c = 0; c < r.clouds; ++c) {
    const double stamp = 100.1 + 0.1 * c;
    std::vector<sensors::ScanPoint> points;
    for (int i = 0; i < 100; ++i) {
      points.push_back({float(5.0 + 0.01 * i), 0.0f, 0.0f, 10.0f, std::uint16_t(i % 16),
                        float(-0.1 + 0.001 * i)});
    }
    const std::string frame = c == r.odd_frame_cloud ? "laser" : r.cloud_frame;
    bag.write(cloud, at(stamp), formats::ros1::pointCloud2(points, at(stamp), c, frame));
  }
  bag.close();
  return path;
}

class BagImport : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = formats::test_files::scratchFolder("bag_import"); }
  void TearDown() override { fs::remove_all(dir_); }
  BagImportSummary import(const Recording& r, const BagImportOptions& options = {}) {
    return importRosbag(writeBag(dir_, r), (dir_ / "ds").string(), options, nullptr);
  }
  nlohmann::json metadata() const {
    return nlohmann::json::parse(std::ifstream(dir_ / "ds" / "metadata.json"));
  }
  fs::path dir_;
};

TEST_F(BagImport, ARecordingBecomesADatasetInItsOwnTime) {
  const BagImportSummary summary = import(Recording{});
  EXPECT_EQ(summary.lidar.topic, "/velodyne_points");
  EXPECT_EQ(summary.lidar.messages, 10u);
  EXPECT_EQ(summary.odometry.topic, "/odom");
  EXPECT_EQ(summary.imu.topic, "/imu/data");
  EXPECT_EQ(summary.stamp, "last_packet");  // most points come before the stamp
  EXPECT_NEAR(summary.scan_period, 0.1, 1e-9);
  // Dataset time 0 is the whole second at or before the first stamp (100 s): the first cloud
  // at 0.1 s, the odometry's first pose at 0 at the origin, 0.5 m further each second.
  const common::Trajectory odometry = common::readTum((dir_ / "ds" / "odometry.tum").string());
  ASSERT_FALSE(odometry.empty());
  EXPECT_NEAR(odometry.front().t, 0.0, 1e-9);
  EXPECT_NEAR(odometry.back().t, 1.1, 1e-9);
  EXPECT_NEAR(odometry.back().pose.translation().x(), 0.55, 1e-6);
  for (int k = 0; k < 10; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "%06d.pcd", k);
    EXPECT_EQ(formats::readPcd((dir_ / "ds" / "scans" / name).string()).size(), 100u) << name;
  }
  EXPECT_FALSE(fs::exists(dir_ / "ds" / "scans" / "000010.pcd"));
  // The mounts from /tf_static, the IMU at rest in m/s².
  const nlohmann::json m = metadata();
  EXPECT_EQ(m["format"], "isg.dataset");
  EXPECT_EQ(m["extrinsics"]["R_T_L"]["xyz_rpy"][2], 0.5);
  EXPECT_EQ(m["extrinsics"]["R_T_I"]["xyz_rpy"][0], -0.1);
  EXPECT_EQ(m["frames"]["L"], "velodyne");
  EXPECT_EQ(m["lidar"]["scans"], 10);
  EXPECT_NEAR(m["imu"]["rate_hz"].get<double>(), 100.0, 1e-6);
  // The driver's variances are density² × rate: 1e-6 rad²/s² at 100 Hz is 1e-4 rad/s/√Hz.
  EXPECT_NEAR(m["imu"]["gyroscope_noise_density"].get<double>(), 1e-4, 1e-12);
  EXPECT_EQ(m["imported_from"]["file"], "walk.bag");
  EXPECT_EQ(m["imported_from"]["time_origin_s"], 100);
  const auto imu = formats::readImuFile((dir_ / "ds" / "imu.csv").string());
  EXPECT_NEAR(imu.front().accelerometer.z(), 9.81, 1e-9);
}

TEST_F(BagImport, AnImuInGIsConvertedAndSaidSo) {
  Recording r;
  r.gravity = 1.0;
  const BagImportSummary summary = import(r);
  const auto imu = formats::readImuFile((dir_ / "ds" / "imu.csv").string());
  EXPECT_NEAR(imu.front().accelerometer.z(), 9.80665, 1e-9);
  bool said = false;
  for (const auto& note : summary.notes) said = said || note.find("in g") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST_F(BagImport, AWindowOfTheRecording) {
  BagImportOptions options;
  options.start = 0.45;  // the bag's first message is at 100 s
  options.duration = 0.4;
  const BagImportSummary summary = import(Recording{}, options);
  // Clouds stamped 100.5 … 100.8 s lie in [100.45, 100.85].
  EXPECT_EQ(summary.lidar.messages, 4u);
  EXPECT_EQ(metadata()["imported_from"]["start_s"], 0.45);
}

TEST_F(BagImport, ACloudInAnotherFrameIsNamedAndNothingIsWritten) {
  Recording r;
  r.odd_frame_cloud = 3;
  try {
    import(r);
    FAIL() << "imported";
  } catch (const common::InputError& e) {
    EXPECT_EQ(e.reason(),
              "topic /velodyne_points, message 3: its frame \"laser\" is not the first cloud's "
              "\"velodyne\"");
  }
  EXPECT_FALSE(fs::exists(dir_ / "ds"));
}

TEST_F(BagImport, AMountMissingFromTheRecordingIsAskedFor) {
  Recording r;
  r.cloud_frame = "lidar";  // /tf_static joins velodyne, not lidar, to the base
  try {
    import(r);
    FAIL() << "imported";
  } catch (const common::InputError& e) {
    EXPECT_NE(e.reason().find("--lidar-extrinsic"), std::string::npos) << e.reason();
  }
  BagImportOptions options;
  options.lidar_extrinsic = std::array<double, 6>{0.2, 0, 0.4, 0, 0, 0};
  import(r, options);
  EXPECT_EQ(metadata()["extrinsics"]["R_T_L"]["xyz_rpy"][0], 0.2);
}

// tf's frames form a tree: a cycle, on /tf or /tf_static, is refused naming its frames, never
// imported with one of its links dropped unsaid.
TEST_F(BagImport, ACycleOfFramesIsRefusedNamingItsFrames) {
  Recording on_tf;
  on_tf.odometry_on_tf = true;
  import(on_tf);  // odom → base_link on /tf alone is odometry
  EXPECT_EQ(metadata()["imported_from"]["topics"]["odometry"], "/tf");
  fs::remove_all(dir_ / "ds");
  on_tf.tf_back_link = true;
  try {
    import(on_tf);
    FAIL() << "imported";
  } catch (const common::InputError& e) {
    EXPECT_EQ(e.reason(),
              "topic /tf, message 0: the transform \"base_link\" → \"odom\" closes a cycle of "
              "frames (odom → base_link → odom); tf's frames form a tree; --odom-topic none "
              "leaves /tf out");
  }
  EXPECT_FALSE(fs::exists(dir_ / "ds"));
  Recording on_static;
  on_static.more_static = {{"velodyne", "base_link"}};
  try {
    import(on_static);
    FAIL() << "imported";
  } catch (const common::InputError& e) {
    EXPECT_EQ(e.reason(),
              "topic /tf_static, message 1: the transform \"velodyne\" → \"base_link\" closes "
              "a cycle of frames (base_link → velodyne → base_link); tf's frames form a tree");
  }
  on_static.more_static = {{"imu_link", "imu_link"}};
  try {
    import(on_static);
    FAIL() << "imported";
  } catch (const common::InputError& e) {
    EXPECT_EQ(e.reason(), "topic /tf_static, message 1: the frame \"imu_link\" hangs from itself");
  }
  EXPECT_FALSE(fs::exists(dir_ / "ds"));
}

// A bag of a driver's raw packets and no point clouds (a real Ouster driver's): refused saying so,
// listing the packet topics and what the import decodes, never suggesting --lidar-topic.
TEST_F(BagImport, PacketsWithoutCloudsAreNamedForWhatTheyAre) {
  const std::string path = (dir_ / "packets.bag").string();
  {
    formats::RosbagWriter bag(path, true);
    const formats::RosMessageType packet{"ouster_ros/PacketMsg", "4f7b5949e76f86d01e96b0e33ba9b5e3",
                                         "uint8[] buf\n"};
    const int lidar = bag.connect("/os_node/lidar_packets", packet);
    const int imu = bag.connect("/os_node/imu_packets", packet);
    const std::string buf(4 + 16, '\0');  // a uint8[] of 16 bytes: its length, then the bytes
    std::string message = buf;
    message[0] = 16;
    for (int k = 0; k < 3; ++k) {
      bag.write(lidar, formats::RosTime::fromSeconds(100.0 + 0.01 * k), message);
    }
    bag.write(imu, formats::RosTime::fromSeconds(100.0), message);
    bag.close();
  }
  try {
    importRosbag(path, (dir_ / "ds").string(), {}, nullptr);
    FAIL() << "imported";
  } catch (const common::InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.reason(),
              "the bag has no point clouds (sensor_msgs/PointCloud2), only a LiDAR's raw packets: "
              "/os_node/imu_packets (ouster_ros/PacketMsg, 1 message), /os_node/lidar_packets "
              "(ouster_ros/PacketMsg, 3 messages); the import reads point clouds and decodes no "
              "packet type but Velodyne's VLP-16 packets (velodyne_msgs/VelodyneScan): record the "
              "driver's point-cloud topic, or play the bag through the driver and record its "
              "clouds");
    EXPECT_EQ(e.reason().find("--lidar-topic"), std::string::npos);
  }
  BagImportOptions named;
  named.lidar_topic = "/os_node/lidar_packets";
  try {
    importRosbag(path, (dir_ / "ds").string(), named, nullptr);
    FAIL() << "imported";
  } catch (const common::InputError& e) {
    EXPECT_EQ(e.reason(),
              "--lidar-topic /os_node/lidar_packets: the topic carries ouster_ros/PacketMsg, the "
              "LiDAR must be sensor_msgs/PointCloud2 or velodyne_msgs/VelodyneScan (a LiDAR's raw "
              "packets, which the import does not decode: record the driver's point-cloud topic)");
  }
  EXPECT_FALSE(fs::exists(dir_ / "ds"));
}

// The real VLP-16 packets of formats/tests/data/vlp16-real (a ROS 2 bag of 4 VelodyneScan messages,
// 603 packets, dual return): decoded and cut into turns, the turns the recording holds whole
// become scans; the same packets in a ROS 1 bag (serialised here: Header, then each packet's
// time and uint8[1206]) give the same scans, byte for byte.
TEST_F(BagImport, VelodynePacketsOfEitherRosBecomeScans) {
  const std::string db3 =
      std::string(ISG_SOURCE_DIR) + "/formats/tests/data/vlp16-real/nebula-vlp16-indoor.db3";
  const BagImportSummary summary = importRosbag(db3, (dir_ / "ros2").string(), {}, nullptr);
  EXPECT_EQ(summary.lidar.topic, "/velodyne_packets");
  EXPECT_EQ(summary.lidar.type, "velodyne_msgs/msg/VelodyneScan");
  EXPECT_EQ(summary.cloud_layout, "x y z intensity ring time (VLP-16 packets decoded)");
  EXPECT_EQ(summary.stamp, "first_firing");
  ASSERT_FALSE(summary.notes.empty());
  EXPECT_EQ(summary.notes[0].rfind("603 VLP-16 packets decoded (dual return) into ", 0), 0u)
      << summary.notes[0];
  // 0.4 s of a head turning at 10 Hz: whole turns between the first and the last crossing.
  ASSERT_GE(summary.lidar.messages, 2u);
  ASSERT_LE(summary.lidar.messages, 3u);
  EXPECT_NEAR(summary.scan_period, 0.1, 0.005);
  EXPECT_GE(summary.point_time[0], 0.0);
  EXPECT_NEAR(summary.point_time[1], 0.1, 0.005);
  // One echo a shot: about as many points a turn as tier4/nebula's decoder gives for one of these
  // turns (formats/tests/data/vlp16-real: 14 831 points, both echoes where they differ, cut at
  // another azimuth), and never more than the 16 × ~1800 shots of a turn at 10 Hz.
  for (std::uint64_t k = 0; k < summary.lidar.messages; ++k) {
    const auto scan =
        formats::readPcd((dir_ / "ros2/scans" / formats::dataset::scanFileName(int(k))).string());
    EXPECT_NEAR(double(scan.size()), 14831.0, 0.05 * 14831.0);
    EXPECT_LT(scan.size(), 16u * 1850u);
  }

  // The same packets as ROS 1 messages.
  const std::string bag_path = (dir_ / "packets.bag").string();
  {
    formats::RosbagWriter bag(bag_path, true);
    const formats::RosMessageType type{"velodyne_msgs/VelodyneScan",
                                       "50804fc9533a0e579e6322c04ae70566", "Header header\n"};
    const int topic = bag.connect("/velodyne_packets", type);
    formats::Ros2Bag ros2(db3);
    ros2.read({"/velodyne_packets"}, [&](const formats::Ros2MessageView& m) {
      const auto scan = formats::ros2::decodeVelodyneScan(m.data);
      std::string out;
      const auto put = [&](std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
      put(0);
      put(scan.header.stamp.sec);
      put(scan.header.stamp.nsec);
      put(std::uint32_t(scan.header.frame_id.size()));
      out += scan.header.frame_id;
      put(std::uint32_t(scan.packets.size()));
      for (const auto& packet : scan.packets) {
        put(packet.stamp.sec);
        put(packet.stamp.nsec);
        out += packet.data;
      }
      const auto ns = std::uint64_t(m.stamp_ns);
      bag.write(topic, {std::uint32_t(ns / 1000000000u), std::uint32_t(ns % 1000000000u)}, out);
      return true;
    });
    bag.close();
  }
  const BagImportSummary ros1 = importRosbag(bag_path, (dir_ / "ros1").string(), {}, nullptr);
  EXPECT_EQ(ros1.lidar.type, "velodyne_msgs/VelodyneScan");
  ASSERT_EQ(ros1.lidar.messages, summary.lidar.messages);
  for (const char* file : {"scans.txt", "scans/000000.pcd", "scans/000001.pcd"}) {
    std::ifstream a(dir_ / "ros1" / file, std::ios::binary),
        b(dir_ / "ros2" / file, std::ios::binary);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(a), {}),
              std::string(std::istreambuf_iterator<char>(b), {}))
        << file;
  }
}

}  // namespace
}  // namespace isg::recordings
