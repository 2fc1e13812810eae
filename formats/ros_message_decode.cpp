#include "formats/ros_message_decode.hpp"

#include <cmath>
#include <cstring>

namespace isg::formats::ros1 {

namespace {

// Little-endian reads with the bounds checked, naming the field that did not fit.
class Cursor {
 public:
  explicit Cursor(std::string_view bytes) : bytes_(bytes) {}

  template <typename T>
  T number(const char* field) {
    T value;
    std::memcpy(&value, take(sizeof(T), field).data(), sizeof(T));
    return value;
  }
  std::string_view take(std::size_t size, const char* field) {
    if (size > bytes_.size() - position_) {
      throw MessageError("truncated at byte " + std::to_string(position_) + " of " +
                         std::to_string(bytes_.size()) + " (the field `" + field + "` needs " +
                         std::to_string(size) + " bytes)");
    }
    const std::string_view out = bytes_.substr(position_, size);
    position_ += size;
    return out;
  }
  std::string string(const char* field) { return std::string(take(length(field, 1), field)); }
  // An array's element count, checked against the bytes left at `min_element_size` each, so that
  // a corrupt count is an error, not a huge allocation.
  std::uint32_t length(const char* field, std::size_t min_element_size) {
    const auto count = number<std::uint32_t>(field);
    if (std::uint64_t(count) * min_element_size > bytes_.size() - position_) {
      throw MessageError("the field `" + std::string(field) + "` claims " + std::to_string(count) +
                         " elements at byte " + std::to_string(position_ - 4) + ", more than the " +
                         std::to_string(bytes_.size() - position_) + " bytes left");
    }
    return count;
  }
  double real(const char* field) { return number<double>(field); }
  Eigen::Vector3d vector(const char* field) {
    const double x = real(field), y = real(field), z = real(field);
    return {x, y, z};
  }
  Eigen::Quaterniond quaternion(const char* field) {
    const double x = real(field), y = real(field), z = real(field), w = real(field);
    return Eigen::Quaterniond(w, x, y, z);
  }
  void finish(const char* type) const {
    if (position_ != bytes_.size()) {
      throw MessageError(std::to_string(bytes_.size() - position_) + " bytes left over after a " +
                         type + " of " + std::to_string(position_) + " bytes");
    }
  }

 private:
  std::string_view bytes_;
  std::size_t position_ = 0;
};

Header rosHeader(Cursor& in) {
  Header h;
  h.seq = in.number<std::uint32_t>("header.seq");
  h.stamp.sec = in.number<std::uint32_t>("header.stamp");
  h.stamp.nsec = in.number<std::uint32_t>("header.stamp");
  if (h.stamp.nsec >= 1000000000u) {
    throw MessageError("header.stamp has " + std::to_string(h.stamp.nsec) +
                       " nanoseconds (at most 999999999)");
  }
  h.frame_id = in.string("header.frame_id");
  return h;
}

Eigen::Isometry3d rosPose(Cursor& in, const char* position, const char* orientation) {
  const Eigen::Vector3d t = in.vector(position);
  // Said before the rotation is read, as it always was.
  if (!t.allFinite()) throw MessageError(std::string("the field `") + position + "` is not finite");
  return checkedPose(t, in.quaternion(orientation), position, orientation);
}

template <std::size_t N>
std::array<double, N> rosReals(Cursor& in, const char* field) {
  std::array<double, N> out;
  for (auto& value : out) value = in.real(field);
  return out;
}

}  // namespace

Eigen::Quaterniond unitRotation(Eigen::Quaterniond q, const char* field) {
  const double norm = q.norm();
  if (!std::isfinite(norm) || std::abs(norm - 1.0) > 1e-3) {
    throw MessageError(std::string("the field `") + field + "` is not a unit quaternion (norm " +
                       std::to_string(norm) + ")");
  }
  q.normalize();
  return q;
}

Eigen::Isometry3d checkedPose(const Eigen::Vector3d& t, const Eigen::Quaterniond& q,
                              const char* position, const char* orientation) {
  if (!t.allFinite()) throw MessageError(std::string("the field `") + position + "` is not finite");
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = unitRotation(q, orientation).toRotationMatrix();
  out.translation() = t;
  return out;
}

PointCloud2 decodePointCloud2(std::string_view bytes) {
  Cursor in(bytes);
  PointCloud2 cloud;
  cloud.header = rosHeader(in);
  cloud.height = in.number<std::uint32_t>("height");
  cloud.width = in.number<std::uint32_t>("width");
  const std::uint32_t fields = in.length("fields", 13);
  for (std::uint32_t i = 0; i < fields; ++i) {
    PointField field;
    field.name = in.string("fields.name");
    field.offset = in.number<std::uint32_t>("fields.offset");
    field.datatype = in.number<std::uint8_t>("fields.datatype");
    field.count = in.number<std::uint32_t>("fields.count");
    cloud.fields.push_back(field);
  }
  cloud.is_bigendian = in.number<std::uint8_t>("is_bigendian") != 0;
  cloud.point_step = in.number<std::uint32_t>("point_step");
  cloud.row_step = in.number<std::uint32_t>("row_step");
  cloud.data = in.take(in.length("data", 1), "data");
  cloud.is_dense = in.number<std::uint8_t>("is_dense") != 0;
  in.finish("sensor_msgs/PointCloud2");
  return cloud;
}

Imu decodeImu(std::string_view bytes) {
  Cursor in(bytes);
  Imu imu;
  imu.header = rosHeader(in);
  // An IMU without orientation may write zeros there (the message says: covariance[0] = -1).
  imu.orientation = in.quaternion("orientation");
  imu.orientation_covariance = rosReals<9>(in, "orientation_covariance");
  imu.angular_velocity = in.vector("angular_velocity");
  imu.angular_velocity_covariance = rosReals<9>(in, "angular_velocity_covariance");
  imu.linear_acceleration = in.vector("linear_acceleration");
  imu.linear_acceleration_covariance = rosReals<9>(in, "linear_acceleration_covariance");
  in.finish("sensor_msgs/Imu");
  if (!imu.angular_velocity.allFinite() || !imu.linear_acceleration.allFinite()) {
    throw MessageError("a rate or an acceleration is not finite");
  }
  return imu;
}

StampedPose decodeOdometry(std::string_view bytes) {
  Cursor in(bytes);
  StampedPose out;
  out.header = rosHeader(in);
  out.child_frame_id = in.string("child_frame_id");
  out.pose = rosPose(in, "pose.pose.position", "pose.pose.orientation");
  rosReals<36>(in, "pose.covariance");
  rosReals<6>(in, "twist.twist");
  rosReals<36>(in, "twist.covariance");
  in.finish("nav_msgs/Odometry");
  return out;
}

StampedPose decodePoseStamped(std::string_view bytes) {
  Cursor in(bytes);
  StampedPose out;
  out.header = rosHeader(in);
  out.pose = rosPose(in, "pose.position", "pose.orientation");
  in.finish("geometry_msgs/PoseStamped");
  return out;
}

std::vector<TransformStamped> decodeTfMessage(std::string_view bytes) {
  Cursor in(bytes);
  std::vector<TransformStamped> out;
  // Each transform has at least a rosHeader (16 bytes), a child frame (4) and 7 float64.
  const std::uint32_t count = in.length("transforms", 16 + 4 + 56);
  for (std::uint32_t i = 0; i < count; ++i) {
    TransformStamped t;
    t.header = rosHeader(in);
    t.child_frame_id = in.string("transforms.child_frame_id");
    t.parent_T_child =
        rosPose(in, "transforms.transform.translation", "transforms.transform.rotation");
    out.push_back(std::move(t));
  }
  in.finish("tf2_msgs/TFMessage");
  return out;
}

std::string decodeString(std::string_view bytes) {
  Cursor in(bytes);
  std::string out = in.string("data");
  in.finish("std_msgs/String");
  return out;
}

VelodyneScan decodeVelodyneScan(std::string_view bytes) {
  Cursor in(bytes);
  VelodyneScan scan;
  scan.header = rosHeader(in);
  // Each packet is its stamp (8 bytes) and a fixed uint8[1206]: the count is checked against
  // that before anything is allocated.
  const std::uint32_t count = in.length("packets", 8 + kVelodynePacketBytes);
  scan.packets.reserve(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    VelodynePacket packet;
    packet.stamp.sec = in.number<std::uint32_t>("packets[].stamp");
    packet.stamp.nsec = in.number<std::uint32_t>("packets[].stamp");
    if (packet.stamp.nsec >= 1000000000u) {
      throw MessageError("packets[" + std::to_string(i) + "].stamp has " +
                         std::to_string(packet.stamp.nsec) + " nanoseconds (at most 999999999)");
    }
    packet.data = std::string(in.take(kVelodynePacketBytes, "packets[].data"));
    scan.packets.push_back(std::move(packet));
  }
  in.finish("velodyne_msgs/VelodyneScan");
  return scan;
}

}  // namespace isg::formats::ros1
