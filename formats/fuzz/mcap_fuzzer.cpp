// libFuzzer harness: bytes → the MCAP reader, every message read and decoded from CDR as its
// channel's schema says, as the ROS 2 import will (clouds down to their points).
#include <cstdint>
#include <string>

#include "common/input_error.hpp"
#include "formats/cloud_layout.hpp"
#include "formats/mcap_reader.hpp"
#include "formats/ros2_message_decode.hpp"

namespace {

void decode(const isg::formats::McapMessageView& m) {
  namespace ros1 = isg::formats::ros1;
  namespace ros2 = isg::formats::ros2;
  const std::string& type = m.channel->schema_name;
  try {
    if (type == "sensor_msgs/msg/PointCloud2") {
      const ros1::PointCloud2 cloud = ros2::decodePointCloud2(m.data);
      isg::formats::cloudPoints(cloud, isg::formats::cloudLayout(cloud));
    } else if (type == "sensor_msgs/msg/Imu") {
      ros2::decodeImu(m.data);
    } else if (type == "nav_msgs/msg/Odometry") {
      ros2::decodeOdometry(m.data);
    } else if (type == "geometry_msgs/msg/PoseStamped") {
      ros2::decodePoseStamped(m.data);
    } else if (type == "tf2_msgs/msg/TFMessage") {
      ros2::decodeTfMessage(m.data);
    } else if (type == "velodyne_msgs/msg/VelodyneScan") {
      ros2::decodeVelodyneScan(m.data);
    } else {
      ros2::decodeString(m.data);
    }
  } catch (const ros1::MessageError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    isg::formats::McapReader reader(std::string(reinterpret_cast<const char*>(data), size),
                                    "fuzz.mcap");
    reader.read({}, [&](const isg::formats::McapMessageView& m) {
      decode(m);
      return true;
    });
  } catch (const isg::common::InputError&) {
  }
  return 0;
}
