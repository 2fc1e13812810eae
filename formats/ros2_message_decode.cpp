#include "formats/ros2_message_decode.hpp"

#include <array>
#include <cmath>

#include "formats/cdr_reader.hpp"

namespace isg::formats::ros2 {

namespace {

using ros1::MessageError;

ros1::Header cdrHeader(CdrReader& in) {
  ros1::Header h;
  const std::int32_t sec = in.i32("header.stamp");
  const std::uint32_t nanosec = in.u32("header.stamp");
  if (sec < 0) throw MessageError("header.stamp is " + std::to_string(sec) + " s, before 1970");
  if (nanosec >= 1000000000u) {
    throw MessageError("header.stamp has " + std::to_string(nanosec) +
                       " nanoseconds (at most 999999999)");
  }
  h.stamp.sec = std::uint32_t(sec);
  h.stamp.nsec = nanosec;
  h.frame_id = in.string("header.frame_id");
  return h;
}

Eigen::Vector3d cdrVector(CdrReader& in, const char* field) {
  const double x = in.f64(field), y = in.f64(field), z = in.f64(field);
  return {x, y, z};
}

Eigen::Quaterniond cdrQuaternion(CdrReader& in, const char* field) {
  const double x = in.f64(field), y = in.f64(field), z = in.f64(field), w = in.f64(field);
  return Eigen::Quaterniond(w, x, y, z);
}

Eigen::Isometry3d cdrPose(CdrReader& in, const char* position, const char* orientation) {
  const Eigen::Vector3d t = cdrVector(in, position);
  if (!t.allFinite()) throw MessageError(std::string("the field `") + position + "` is not finite");
  return ros1::checkedPose(t, cdrQuaternion(in, orientation), position, orientation);
}

template <std::size_t N>
std::array<double, N> cdrReals(CdrReader& in, const char* field) {
  std::array<double, N> out;
  for (auto& value : out) value = in.f64(field);
  return out;
}

// Runs `decode` over a reader of `bytes`, CDR's complaints as MessageErrors.
template <typename Decode>
auto decodedCdr(std::string_view bytes, Decode decode) {
  try {
    CdrReader in(bytes);
    return decode(in);
  } catch (const CdrError& e) {
    throw MessageError(e.what());
  }
}

}  // namespace

ros1::PointCloud2 decodePointCloud2(std::string_view bytes) {
  return decodedCdr(bytes, [](CdrReader& in) {
    ros1::PointCloud2 cloud;
    cloud.header = cdrHeader(in);
    cloud.height = in.u32("height");
    cloud.width = in.u32("width");
    // A field takes at least its name's count and NUL, offset, datatype and count: 13 bytes.
    const std::uint32_t fields = in.count(13, "fields");
    for (std::uint32_t i = 0; i < fields; ++i) {
      ros1::PointField field;
      field.name = in.string("fields.name");
      field.offset = in.u32("fields.offset");
      field.datatype = in.u8("fields.datatype");
      field.count = in.u32("fields.count");
      cloud.fields.push_back(field);
    }
    cloud.is_bigendian = in.boolean("is_bigendian");
    cloud.point_step = in.u32("point_step");
    cloud.row_step = in.u32("row_step");
    cloud.data = in.bytes(in.count(1, "data"), "data");
    cloud.is_dense = in.boolean("is_dense");
    in.expectEnd("a sensor_msgs/msg/PointCloud2");
    return cloud;
  });
}

ros1::Imu decodeImu(std::string_view bytes) {
  return decodedCdr(bytes, [](CdrReader& in) {
    ros1::Imu imu;
    imu.header = cdrHeader(in);
    // An IMU without orientation may write zeros there (the message says: covariance[0] = -1).
    imu.orientation = cdrQuaternion(in, "orientation");
    imu.orientation_covariance = cdrReals<9>(in, "orientation_covariance");
    imu.angular_velocity = cdrVector(in, "angular_velocity");
    imu.angular_velocity_covariance = cdrReals<9>(in, "angular_velocity_covariance");
    imu.linear_acceleration = cdrVector(in, "linear_acceleration");
    imu.linear_acceleration_covariance = cdrReals<9>(in, "linear_acceleration_covariance");
    in.expectEnd("a sensor_msgs/msg/Imu");
    if (!imu.angular_velocity.allFinite() || !imu.linear_acceleration.allFinite()) {
      throw MessageError("a rate or an acceleration is not finite");
    }
    return imu;
  });
}

ros1::StampedPose decodeOdometry(std::string_view bytes) {
  return decodedCdr(bytes, [](CdrReader& in) {
    ros1::StampedPose out;
    out.header = cdrHeader(in);
    out.child_frame_id = in.string("child_frame_id");
    out.pose = cdrPose(in, "pose.pose.position", "pose.pose.orientation");
    cdrReals<36>(in, "pose.covariance");
    cdrReals<6>(in, "twist.twist");
    cdrReals<36>(in, "twist.covariance");
    in.expectEnd("a nav_msgs/msg/Odometry");
    return out;
  });
}

ros1::StampedPose decodePoseStamped(std::string_view bytes) {
  return decodedCdr(bytes, [](CdrReader& in) {
    ros1::StampedPose out;
    out.header = cdrHeader(in);
    out.pose = cdrPose(in, "pose.position", "pose.orientation");
    in.expectEnd("a geometry_msgs/msg/PoseStamped");
    return out;
  });
}

std::vector<ros1::TransformStamped> decodeTfMessage(std::string_view bytes) {
  return decodedCdr(bytes, [](CdrReader& in) {
    std::vector<ros1::TransformStamped> out;
    // Each transform has at least a stamp (8 bytes), a frame (4), a child frame (4) and 7 float64.
    const std::uint32_t count = in.count(8 + 4 + 4 + 56, "transforms");
    for (std::uint32_t i = 0; i < count; ++i) {
      ros1::TransformStamped t;
      t.header = cdrHeader(in);
      t.child_frame_id = in.string("transforms.child_frame_id");
      t.parent_T_child =
          cdrPose(in, "transforms.transform.translation", "transforms.transform.rotation");
      out.push_back(std::move(t));
    }
    in.expectEnd("a tf2_msgs/msg/TFMessage");
    return out;
  });
}

std::string decodeString(std::string_view bytes) {
  return decodedCdr(bytes, [](CdrReader& in) {
    std::string out = in.string("data");
    in.expectEnd("a std_msgs/msg/String");
    return out;
  });
}

ros1::VelodyneScan decodeVelodyneScan(std::string_view bytes) {
  return decodedCdr(bytes, [](CdrReader& in) {
    ros1::VelodyneScan scan;
    scan.header = cdrHeader(in);
    const std::uint32_t count = in.u32("packets");
    // Each packet takes at least its stamp and data: a count beyond that is damage, not memory.
    const std::size_t most = in.remaining() / (8 + ros1::kVelodynePacketBytes);
    if (count > most) {
      in.fail(std::to_string(count) + " packets announced, the message holds at most " +
              std::to_string(most));
    }
    scan.packets.reserve(count);
    for (std::uint32_t i = 0; i < count; ++i) {
      ros1::VelodynePacket packet;
      const std::int32_t sec = in.i32("packets[].stamp");
      const std::uint32_t nanosec = in.u32("packets[].stamp");
      if (sec < 0 || nanosec >= 1000000000u) {
        in.fail("packets[" + std::to_string(i) + "].stamp is not a time after 1970 (" +
                std::to_string(sec) + " s, " + std::to_string(nanosec) + " ns)");
      }
      packet.stamp = {std::uint32_t(sec), nanosec};
      packet.data = std::string(in.bytes(ros1::kVelodynePacketBytes, "packets[].data"));
      scan.packets.push_back(std::move(packet));
    }
    if (in.remaining() > 3) {  // CDR pads a message to 4 bytes, no more
      in.fail(std::to_string(in.remaining()) + " bytes after the last packet");
    }
    return scan;
  });
}

}  // namespace isg::formats::ros2
