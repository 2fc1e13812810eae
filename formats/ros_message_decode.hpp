#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "formats/ros_time.hpp"

namespace isg::formats::ros1 {

// ROS 1 messages read back from a recording's bytes, with every length checked against what is
// left: a recording is untrusted input, and Debian's roscpp deserialisers allocate whatever length
// a message claims before finding it is not there. Each decoder reads one message type as its
// .msg defines it (the types a recording's connections must name, with these MD5 sums), and
// throws MessageError saying what is wrong ("truncated at byte 41 of 60 (the field `data`)").

struct MessageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Header {
  std::uint32_t seq = 0;
  RosTime stamp;
  std::string frame_id;
};

// A PointCloud2's field: its name, byte offset in a point, PointField datatype (1 int8 … 8
// float64) and count.
struct PointField {
  std::string name;
  std::uint32_t offset = 0;
  std::uint8_t datatype = 0;
  std::uint32_t count = 0;
};

struct PointCloud2 {
  Header header;
  std::uint32_t height = 0, width = 0;
  std::vector<PointField> fields;
  bool is_bigendian = false;
  std::uint32_t point_step = 0, row_step = 0;
  std::string_view data;  // a view of the decoded bytes: they must outlive it
  bool is_dense = false;
};

struct Imu {
  Header header;
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  std::array<double, 9> orientation_covariance{};
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();
  std::array<double, 9> angular_velocity_covariance{};
  Eigen::Vector3d linear_acceleration = Eigen::Vector3d::Zero();
  std::array<double, 9> linear_acceleration_covariance{};
};

// nav_msgs/Odometry and geometry_msgs/PoseStamped: the pose of `child_frame_id` (empty for a
// PoseStamped) in header.frame_id.
struct StampedPose {
  Header header;
  std::string child_frame_id;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};

struct TransformStamped {
  Header header;
  std::string child_frame_id;
  Eigen::Isometry3d parent_T_child = Eigen::Isometry3d::Identity();
};

// A unit quaternion within 1e-3 (what drivers write in float64), normalised; anything else is
// not a rotation and would skew every pose composed with it (MessageError naming `field`).
Eigen::Quaterniond unitRotation(Eigen::Quaterniond q, const char* field);
// A finite translation and a unit rotation as a pose, checked as unitRotation does.
Eigen::Isometry3d checkedPose(const Eigen::Vector3d& t, const Eigen::Quaterniond& q,
                              const char* position, const char* orientation);

PointCloud2 decodePointCloud2(std::string_view bytes);
Imu decodeImu(std::string_view bytes);
StampedPose decodeOdometry(std::string_view bytes);
StampedPose decodePoseStamped(std::string_view bytes);
std::vector<TransformStamped> decodeTfMessage(std::string_view bytes);
std::string decodeString(std::string_view bytes);

// velodyne_msgs/VelodyneScan: the Velodyne driver's raw packets of one turn, each its receive
// stamp and its 1206-byte UDP payload (a packet of another size is refused).
// The payload of a Velodyne data packet (VLP-16, VLP-32C, HDL-32E: formats/vlp16_packet.hpp).
inline constexpr std::size_t kVelodynePacketBytes = 1206;
struct VelodynePacket {
  RosTime stamp;
  std::string data;
};
struct VelodyneScan {
  Header header;
  std::vector<VelodynePacket> packets;
};
VelodyneScan decodeVelodyneScan(std::string_view bytes);

}  // namespace isg::formats::ros1
