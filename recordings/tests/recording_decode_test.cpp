// What a recording's messages are read into: the checked ROS 1 decoders against our own
// encoders (Debian's message headers), the clouds' layouts by field name and type, the fixed
// frames' tree, and scans.txt.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "common/input_error.hpp"
#include "formats/cloud_layout.hpp"
#include "formats/ros_message_decode.hpp"
#include "formats/ros_messages.hpp"
#include "formats/trajectory_file.hpp"
#include "recordings/static_frames.hpp"
#include "sensors/mount_transform.hpp"

namespace isg::recordings {
namespace {

using ::testing::HasSubstr;

TEST(RecordingDecode, MessagesReadBackWhatOurEncodersWrote) {
  const formats::RosTime t{1600000000, 250000000};
  const std::vector<sensors::ScanPoint> points = {{1.0f, 2.0f, 3.0f, 40.0f, 7, 0.05f},
                                                  {-4.0f, 0.5f, -1.0f, 3.0f, 15, 0.099f}};
  // The decoded cloud's data is a view of the message's bytes: they must outlive it.
  const std::string message = formats::ros1::pointCloud2(points, t, 9, "lidar");
  const formats::ros1::PointCloud2 cloud = formats::ros1::decodePointCloud2(message);
  EXPECT_EQ(cloud.header.seq, 9u);
  EXPECT_EQ(cloud.header.stamp.sec, t.sec);
  EXPECT_EQ(cloud.header.stamp.nsec, t.nsec);
  EXPECT_EQ(cloud.header.frame_id, "lidar");
  EXPECT_EQ(cloud.width, 2u);
  EXPECT_EQ(cloud.point_step, 22u);
  const formats::CloudLayout layout = formats::cloudLayout(cloud);
  EXPECT_EQ(layout.describe(), "x y z intensity ring time (the Velodyne driver's layout)");
  const std::vector<sensors::ScanPoint> back = formats::cloudPoints(cloud, layout);
  ASSERT_EQ(back.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(back[i].x, points[i].x);
    EXPECT_EQ(back[i].z, points[i].z);
    EXPECT_EQ(back[i].intensity, points[i].intensity);
    EXPECT_EQ(back[i].ring, points[i].ring);
    EXPECT_EQ(back[i].time, points[i].time);
  }

  sensors::ImuSample sample;
  sample.accelerometer = {0.1, -0.2, 9.81};
  sample.gyroscope = {0.01, 0.02, -0.03};
  const formats::ros1::Imu imu =
      formats::ros1::decodeImu(formats::ros1::imu(sample, t, 3, "imu", 4e-6, 9e-4));
  EXPECT_EQ(imu.header.frame_id, "imu");
  EXPECT_EQ(imu.linear_acceleration, sample.accelerometer);
  EXPECT_EQ(imu.angular_velocity, sample.gyroscope);
  EXPECT_EQ(imu.angular_velocity_covariance[0], 4e-6);
  EXPECT_EQ(imu.linear_acceleration_covariance[8], 9e-4);
  EXPECT_EQ(imu.orientation_covariance[0], -1.0);

  const Eigen::Isometry3d pose = sensors::mountTransform({1.5, -2.0, 0.3, 0.1, -0.2, 2.5});
  const formats::ros1::StampedPose odometry = formats::ros1::decodeOdometry(formats::ros1::odometry(
      pose, Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 0, 0.5), t, 1, "odom", "base_link"));
  EXPECT_EQ(odometry.header.frame_id, "odom");
  EXPECT_EQ(odometry.child_frame_id, "base_link");
  EXPECT_LT((odometry.pose.matrix() - pose.matrix()).cwiseAbs().maxCoeff(), 1e-12);

  const auto transforms = formats::ros1::decodeTfMessage(formats::ros1::tfMessage(
      {{t, "base_link", "velodyne", pose}, {t, "base_link", "imu", pose.inverse()}}));
  ASSERT_EQ(transforms.size(), 2u);
  EXPECT_EQ(transforms[1].child_frame_id, "imu");
  EXPECT_LT((transforms[1].parent_T_child.matrix() - pose.inverse().matrix()).cwiseAbs().maxCoeff(),
            1e-12);
  EXPECT_EQ(formats::ros1::decodeString(formats::ros1::stringMessage("{\"a\": 1}")), "{\"a\": 1}");
}

std::string errorOf(const std::function<void()>& decode) {
  try {
    decode();
  } catch (const formats::ros1::MessageError& e) {
    return e.what();
  }
  return "no error";
}

TEST(RecordingDecode, DamagedMessagesAreExactErrors) {
  const formats::RosTime t{100, 0};
  const std::string cloud = formats::ros1::pointCloud2({{1, 2, 3, 4, 5, 0.0f}}, t, 0, "lidar");
  // Header 4 + 8 + (4 + 5); height, width; then the fields' count.
  EXPECT_EQ(errorOf([&] { formats::ros1::decodePointCloud2(cloud.substr(0, 10)); }),
            "truncated at byte 8 of 10 (the field `header.stamp` needs 4 bytes)");
  EXPECT_EQ(errorOf([&] { formats::ros1::decodePointCloud2(cloud + "x"); }),
            "1 bytes left over after a sensor_msgs/PointCloud2 of " + std::to_string(cloud.size()) +
                " bytes");
  // A field count far beyond the message: an error, not an allocation.
  std::string huge = cloud;
  const std::uint32_t many = 0x7fffffff;
  std::memcpy(huge.data() + 29, &many, 4);
  EXPECT_THAT(errorOf([&] { formats::ros1::decodePointCloud2(huge); }),
              HasSubstr("the field `fields` claims 2147483647 elements at byte 29"));
  // Data shorter than height × width points.
  formats::ros1::PointCloud2 decoded = formats::ros1::decodePointCloud2(cloud);
  decoded.width = 2;
  EXPECT_EQ(errorOf([&] { formats::cloudPoints(decoded, formats::cloudLayout(decoded)); }),
            "1 × 2 points need 44 bytes, the data has 22");
  decoded.width = 1;
  decoded.fields.erase(decoded.fields.begin() + 1);  // no y
  EXPECT_EQ(errorOf([&] { formats::cloudLayout(decoded); }),
            "the cloud has no x, y and z fields (its fields: x z intensity ring time)");
  decoded = formats::ros1::decodePointCloud2(cloud);
  decoded.fields[0].offset = 20;  // x would run past the 22-byte point
  EXPECT_EQ(errorOf([&] { formats::cloudLayout(decoded); }),
            "the field `x` at offset 20 lies outside the point_step of 22 bytes");
  decoded = formats::ros1::decodePointCloud2(cloud);
  decoded.is_bigendian = true;
  EXPECT_EQ(errorOf([&] { formats::cloudLayout(decoded); }), "a big-endian cloud (not read)");
  // A pose whose quaternion is not a rotation.
  std::string odometry =
      formats::ros1::odometry(Eigen::Isometry3d::Identity(), Eigen::Vector3d::Zero(),
                              Eigen::Vector3d::Zero(), t, 0, "odom", "base");
  const double two = 2.0;
  std::memcpy(odometry.data() + 4 + 8 + 4 + 4 + 4 + 4 + 24 + 24, &two, 8);  // orientation.w
  EXPECT_EQ(errorOf([&] { formats::ros1::decodeOdometry(odometry); }),
            "the field `pose.pose.orientation` is not a unit quaternion (norm 2.000000)");
}

// Other drivers' layouts: fields by name, times by type (integers are nanoseconds) and size
// (over 1e6 s: since the epoch).
formats::ros1::PointCloud2 cloudOf(std::vector<formats::ros1::PointField> fields,
                                   std::uint32_t step, const std::string& data,
                                   formats::RosTime stamp) {
  formats::ros1::PointCloud2 cloud;
  cloud.header.stamp = stamp;
  cloud.height = 1;
  cloud.fields = std::move(fields);
  cloud.point_step = step;
  cloud.width = std::uint32_t(data.size() / step);
  cloud.row_step = std::uint32_t(data.size());
  cloud.data = data;
  return cloud;
}

template <typename T>
void put(std::string& data, std::size_t at, T value) {
  std::memcpy(data.data() + at, &value, sizeof value);
}

TEST(RecordingDecode, OtherDriversLayoutsAndTimes) {
  // Ouster: t uint32 ns at 20, ring uint8 at 26, reflectivity uint16 at 24; an empty pixel.
  std::string ouster(48 * 2, '\0');
  put(ouster, 0, 1.0f);
  put(ouster, 8, 0.5f);
  put(ouster, 20, std::uint32_t(51200000));
  put(ouster, 24, std::uint16_t(300));
  put(ouster, 26, std::uint8_t(63));
  const auto o = cloudOf({{"x", 0, 7, 1},
                          {"y", 4, 7, 1},
                          {"z", 8, 7, 1},
                          {"t", 20, 6, 1},
                          {"reflectivity", 24, 4, 1},
                          {"ring", 26, 2, 1}},
                         48, ouster, {1600000000, 0});
  const formats::CloudLayout ouster_layout = formats::cloudLayout(o);
  EXPECT_EQ(ouster_layout.describe(), "x y z reflectivity ring t (Ouster's layout)");
  const auto op = formats::cloudPoints(o, ouster_layout);
  ASSERT_EQ(op.size(), 1u);  // the zero point is no return
  EXPECT_FLOAT_EQ(op[0].time, 0.0512f);
  EXPECT_EQ(op[0].ring, 63);
  EXPECT_EQ(op[0].intensity, 300.0f);
  // Hesai: float64 `timestamp` since the epoch, made relative to the stamp.
  std::string hesai(24, '\0');
  put(hesai, 0, 2.0f);
  put(hesai, 16, 1600000000.0625);
  const auto h = cloudOf({{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}, {"timestamp", 16, 8, 1}},
                         24, hesai, {1600000000, 12500000});
  const auto hp = formats::cloudPoints(h, formats::cloudLayout(h));
  ASSERT_EQ(hp.size(), 1u);
  EXPECT_NEAR(hp[0].time, 0.05, 1e-6);
  // Livox's PointCloud2: float64 `timestamp` in nanoseconds since the epoch, `line` its ring.
  std::string livox(26, '\0');
  put(livox, 0, 4.0f);
  put(livox, 16, std::uint8_t(3));
  put(livox, 18, 1600000000.0625e9);
  const auto l = cloudOf(
      {{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}, {"line", 16, 2, 1}, {"timestamp", 18, 8, 1}},
      26, livox, {1600000000, 12500000});
  const auto lp = formats::cloudPoints(l, formats::cloudLayout(l));
  ASSERT_EQ(lp.size(), 1u);
  EXPECT_NEAR(lp[0].time, 0.05, 1e-6);
  EXPECT_EQ(lp[0].ring, 3);
  EXPECT_EQ(formats::cloudLayout(l).describe(), "x y z line timestamp (Livox's layout)");
  // x y z only: said, and every time 0.
  std::string plain(12, '\0');
  put(plain, 0, 3.0f);
  const auto p = cloudOf({{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}}, 12, plain, {5, 0});
  EXPECT_EQ(formats::cloudLayout(p).describe(),
            "x y z (no per-point time: the scans are not deskewed)");
  EXPECT_EQ(formats::cloudPoints(p, formats::cloudLayout(p))[0].time, 0.0f);
  // A `time` that is no offset from the stamp in any unit read.
  put(hesai, 16, 12.5);
  const auto bad = cloudOf({{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}, {"time", 16, 8, 1}}, 24,
                           hesai, {1600000000, 0});
  EXPECT_EQ(errorOf([&] { formats::cloudPoints(bad, formats::cloudLayout(bad)); }),
            "a point's `time` is 12.500000 s from the cloud's stamp (a turn lasts well under 1 s): "
            "not a time this reads");
}

TEST(RecordingDecode, FixedFramesJoinThroughTheirCommonAncestor) {
  StaticFrames frames;
  const Eigen::Isometry3d base_T_lidar =
      sensors::mountTransform({0.2, 0.0, 0.5, 0.0, 0.0, std::numbers::pi});
  const Eigen::Isometry3d base_T_imu = sensors::mountTransform({-0.1, 0.05, 0.1, 0.0, 0.1, 0.0});
  const Eigen::Isometry3d lidar_T_optical = sensors::mountTransform({0, 0, 0.05, 0, 0, 0.3});
  frames.add("base_link", "velodyne", base_T_lidar);
  frames.add("base_link", "imu_link", base_T_imu);
  frames.add("velodyne", "velodyne_optical", lidar_T_optical);
  const auto near = [](const std::optional<Eigen::Isometry3d>& a, const Eigen::Isometry3d& b) {
    return a && (a->matrix() - b.matrix()).cwiseAbs().maxCoeff() < 1e-12;
  };
  EXPECT_TRUE(near(frames.transform("base_link", "velodyne"), base_T_lidar));
  EXPECT_TRUE(near(frames.transform("velodyne", "base_link"), base_T_lidar.inverse()));
  EXPECT_TRUE(near(frames.transform("imu_link", "velodyne_optical"),
                   base_T_imu.inverse() * base_T_lidar * lidar_T_optical));
  EXPECT_TRUE(near(frames.transform("odom", "odom"), Eigen::Isometry3d::Identity()));
  EXPECT_FALSE(frames.transform("base_link", "os_sensor"));
  // A later transform of the same child replaces the first (tf2's rule).
  frames.add("base_link", "velodyne", base_T_imu);
  EXPECT_TRUE(near(frames.transform("base_link", "velodyne"), base_T_imu));
}

TEST(RecordingDecode, MountAnglesRoundTrip) {
  const std::array<double, 6> mount = {0.1, -0.2, 0.3, 0.4, -0.5, 2.9};
  const auto back = sensors::mountXyzRpy(sensors::mountTransform(mount));
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(back[i], mount[i], 1e-12);
}

TEST(RecordingDecode, ScanStampsFile) {
  const auto file = std::filesystem::temp_directory_path() / "isg_scans_txt_test.txt";
  std::ofstream(file) << "# stamps\n0.100000000\n\n0.200000000\n";
  EXPECT_EQ(formats::readStampsFile(file.string()), (std::vector<double>{0.1, 0.2}));
  std::ofstream(file) << "0.1\n0.1\n";
  try {
    formats::readStampsFile(file.string());
    ADD_FAILURE();
  } catch (const common::InputError& e) {
    EXPECT_EQ(e.reason(), "line 2: the time does not increase");
  }
  std::ofstream(file) << "0.1 2\n";
  try {
    formats::readStampsFile(file.string());
    ADD_FAILURE();
  } catch (const common::InputError& e) {
    EXPECT_EQ(e.reason(), "line 1: expected one time in seconds, got \"0.1 2\"");
  }
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace isg::recordings
