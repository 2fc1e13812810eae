#include "formats/ros2_message_decode.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <string>

#include "formats/cdr_writer.hpp"
#include "formats/ros2_messages.hpp"

namespace isg::formats {
namespace {

std::string decodeErrorOf(const std::function<void()>& decode) {
  try {
    decode();
  } catch (const ros1::MessageError& e) {
    return e.what();
  }
  return "(decoded)";
}

TEST(Ros2Decode, APointCloudReadsBackAsWritten) {
  std::vector<sensors::ScanPoint> points = {{1.0f, 2.0f, 3.0f, 40.0f, 7, 0.05f},
                                            {-1.5f, 0.25f, 0.5f, 12.0f, 15, 0.09f}};
  const std::string bytes = ros2::pointCloud2(points, {1700000000, 123456789}, "velodyne");
  const ros1::PointCloud2 cloud = ros2::decodePointCloud2(bytes);
  EXPECT_EQ(cloud.header.stamp.sec, 1700000000u);
  EXPECT_EQ(cloud.header.stamp.nsec, 123456789u);
  EXPECT_EQ(cloud.header.frame_id, "velodyne");
  EXPECT_EQ(cloud.height, 1u);
  EXPECT_EQ(cloud.width, 2u);
  ASSERT_EQ(cloud.fields.size(), 6u);
  EXPECT_EQ(cloud.fields[4].name, "ring");
  EXPECT_EQ(cloud.fields[4].offset, 16u);
  EXPECT_EQ(cloud.fields[4].datatype, 4);  // uint16
  EXPECT_EQ(cloud.point_step, 22u);
  EXPECT_EQ(cloud.row_step, 44u);
  ASSERT_EQ(cloud.data.size(), 44u);
  float y1;
  std::memcpy(&y1, cloud.data.data() + 22 + 4, 4);
  EXPECT_EQ(y1, 0.25f);
  EXPECT_TRUE(cloud.is_dense);
  EXPECT_FALSE(cloud.is_bigendian);
}

TEST(Ros2Decode, ImuOdometryAndTfReadBackAsWritten) {
  sensors::ImuSample sample;
  sample.gyroscope = {0.1, -0.2, 0.3};
  sample.accelerometer = {0.0, 0.5, 9.81};
  const ros1::Imu imu = ros2::decodeImu(ros2::imu(sample, {5, 0}, "imu", 1e-6, 1e-4));
  EXPECT_EQ(imu.header.frame_id, "imu");
  EXPECT_EQ(imu.angular_velocity, sample.gyroscope);
  EXPECT_EQ(imu.linear_acceleration, sample.accelerometer);
  EXPECT_EQ(imu.orientation_covariance[0], -1.0);
  EXPECT_EQ(imu.angular_velocity_covariance[4], 1e-6);

  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translate(Eigen::Vector3d(1, 2, 0.5));
  pose.rotate(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()));
  const ros1::StampedPose odometry = ros2::decodeOdometry(
      ros2::odometry(pose, {0.5, 0, 0}, {0, 0, 0.1}, {7, 500}, "odom", "base_link"));
  EXPECT_EQ(odometry.header.frame_id, "odom");
  EXPECT_EQ(odometry.child_frame_id, "base_link");
  EXPECT_TRUE(odometry.pose.isApprox(pose, 1e-12));
  EXPECT_EQ(odometry.header.stamp.nsec, 500u);

  const auto transforms = ros2::decodeTfMessage(ros2::tfMessage(
      {{{3, 0}, "base_link", "velodyne", pose}, {{3, 1}, "odom", "base_link", {}}}));
  ASSERT_EQ(transforms.size(), 2u);
  EXPECT_EQ(transforms[0].header.frame_id, "base_link");
  EXPECT_EQ(transforms[0].child_frame_id, "velodyne");
  EXPECT_TRUE(transforms[0].parent_T_child.isApprox(pose, 1e-12));
  EXPECT_EQ(transforms[1].header.stamp.nsec, 1u);
  EXPECT_EQ(ros2::decodeString(ros2::stringMessage("made by isg")), "made by isg");
}

// A geometry_msgs/msg/PoseStamped in big-endian CDR, laid out by hand: header {stamp {sec 2,
// nanosec 3}, frame_id "map"}, then 7 float64 aligned to 8 from the end of the 4-byte header.
TEST(Ros2Decode, BigEndianCdrByHand) {
  std::string b("\x00\x00\x00\x00", 4);  // encapsulation: CDR, big-endian
  const auto be32 = [&](std::uint32_t v) {
    for (int i = 3; i >= 0; --i) b.push_back(char((v >> (8 * i)) & 0xff));
  };
  const auto be64 = [&](double d) {
    std::uint64_t v;
    std::memcpy(&v, &d, 8);
    for (int i = 7; i >= 0; --i) b.push_back(char((v >> (8 * i)) & 0xff));
  };
  be32(2);
  be32(3);
  be32(4);
  b.append("map", 4);  // 12 + 4 = 16 bytes of body: aligned to 8 already
  for (double v : {1.5, -2.0, 0.25}) be64(v);
  for (double v : {0.0, 0.0, std::sin(0.25), std::cos(0.25)}) be64(v);
  const ros1::StampedPose pose = ros2::decodePoseStamped(b);
  EXPECT_EQ(pose.header.stamp.sec, 2u);
  EXPECT_EQ(pose.header.stamp.nsec, 3u);
  EXPECT_EQ(pose.header.frame_id, "map");
  EXPECT_EQ(pose.pose.translation(), Eigen::Vector3d(1.5, -2.0, 0.25));
  EXPECT_NEAR(Eigen::AngleAxisd(pose.pose.linear()).angle(), 0.5, 1e-12);
  // Cut short inside the rotation, and with a frame id that claims more than is there.
  EXPECT_EQ(decodeErrorOf([&] { ros2::decodePoseStamped(b.substr(0, b.size() - 4)); }),
            "ends inside pose.orientation (byte 68 of 72)");
  std::string long_frame = b;
  long_frame[4 + 8 + 3] = 100;
  EXPECT_EQ(decodeErrorOf([&] { ros2::decodePoseStamped(long_frame); }),
            "ends inside header.frame_id (byte 16 of 76)");
}

TEST(Ros2Decode, DamageIsSaidNeverAllocated) {
  EXPECT_EQ(decodeErrorOf([] { ros2::decodeString(std::string("\x00\x01", 2)); }),
            "holds 2 bytes, no CDR header");
  EXPECT_EQ(decodeErrorOf([] { ros2::decodeString(std::string("\x00\x02\x00\x00", 4)); }),
            "encapsulation 0,2 is not plain CDR (0,0 big-endian or 0,1 little-endian)");
  // A cloud whose fields claim four billion elements.
  CdrWriter w;
  w.i32(1);
  w.u32(0);
  w.string("lidar");
  w.u32(1);
  w.u32(10);
  w.u32(0xffffffffu);
  EXPECT_EQ(decodeErrorOf([&] { ros2::decodePointCloud2(w.data()); }),
            "fields: 4294967295 elements announced, the message holds at most 0");
  // Bytes left over after a whole message, and a stamp before 1970.
  std::string text = ros2::stringMessage("ok");
  text.append(8, '\0');
  EXPECT_EQ(decodeErrorOf([&] { ros2::decodeString(text); }),
            "8 bytes after a std_msgs/msg/String (byte 11 of 19)");
  CdrWriter quaternion;
  quaternion.i32(-5);
  quaternion.u32(0);
  quaternion.string("map");
  EXPECT_EQ(decodeErrorOf([&] { ros2::decodePoseStamped(quaternion.data()); }),
            "header.stamp is -5 s, before 1970");
}

}  // namespace
}  // namespace isg::formats
