#include "formats/recorded_message_decode.hpp"

#include "formats/ros2_message_decode.hpp"

namespace isg::formats::recorded {

namespace {

// The decoder of the message's encoding.
template <class Ros1, class Ros2>
auto decodedRecorded(const RecordedMessage& m, Ros1 ros1, Ros2 ros2) {
  switch (m.topic->encoding) {
    case MessageEncoding::kRos1:
      return ros1(m.data);
    case MessageEncoding::kCdr:
      return ros2(m.data);
    case MessageEncoding::kOther:
      break;
  }
  throw ros1::MessageError("encoded as \"" + m.topic->encoding_name +
                           "\": ROS messages are read (ros1 or cdr)");
}

}  // namespace

ros1::PointCloud2 decodePointCloud2(const RecordedMessage& m) {
  return decodedRecorded(m, ros1::decodePointCloud2, ros2::decodePointCloud2);
}
ros1::Imu decodeImu(const RecordedMessage& m) {
  return decodedRecorded(m, ros1::decodeImu, ros2::decodeImu);
}
ros1::StampedPose decodeOdometry(const RecordedMessage& m) {
  return decodedRecorded(m, ros1::decodeOdometry, ros2::decodeOdometry);
}
ros1::StampedPose decodePoseStamped(const RecordedMessage& m) {
  return decodedRecorded(m, ros1::decodePoseStamped, ros2::decodePoseStamped);
}
std::vector<ros1::TransformStamped> decodeTfMessage(const RecordedMessage& m) {
  return decodedRecorded(m, ros1::decodeTfMessage, ros2::decodeTfMessage);
}
std::string decodeString(const RecordedMessage& m) {
  return decodedRecorded(m, ros1::decodeString, ros2::decodeString);
}

ros1::VelodyneScan decodeVelodyneScan(const RecordedMessage& m) {
  return decodedRecorded(m, ros1::decodeVelodyneScan, ros2::decodeVelodyneScan);
}

}  // namespace isg::formats::recorded
