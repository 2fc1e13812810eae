// libFuzzer harness: bytes → the ROS 1 bag reader, every message read and decoded as its
// connection's type says, as isg import does (clouds down to their points).
#include <cstdint>
#include <string>

#include "common/input_error.hpp"
#include "formats/cloud_layout.hpp"
#include "formats/ros_message_decode.hpp"
#include "formats/rosbag_reader.hpp"

namespace {

void decode(const isg::formats::BagMessageView& m) {
  namespace ros1 = isg::formats::ros1;
  const std::string& type = m.connection->type.datatype;
  try {
    if (type == "sensor_msgs/PointCloud2") {
      const ros1::PointCloud2 cloud = ros1::decodePointCloud2(m.data);
      isg::formats::cloudPoints(cloud, isg::formats::cloudLayout(cloud));
    } else if (type == "sensor_msgs/Imu") {
      ros1::decodeImu(m.data);
    } else if (type == "nav_msgs/Odometry") {
      ros1::decodeOdometry(m.data);
    } else if (type == "geometry_msgs/PoseStamped") {
      ros1::decodePoseStamped(m.data);
    } else if (type == "tf2_msgs/TFMessage") {
      ros1::decodeTfMessage(m.data);
    } else {
      ros1::decodeString(m.data);
    }
  } catch (const ros1::MessageError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    isg::formats::RosbagReader reader(std::string(reinterpret_cast<const char*>(data), size),
                                      "fuzz.bag");
    reader.read({}, [&](const isg::formats::BagMessageView& m) {
      decode(m);
      return true;
    });
  } catch (const isg::common::InputError&) {
  }
  return 0;
}
