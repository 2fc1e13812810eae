#pragma once

#include <string>
#include <vector>

#include "formats/recording.hpp"
#include "formats/ros_message_decode.hpp"

namespace isg::formats::recorded {

// A recorded message decoded by its topic's encoding: ROS 1's serialisation
// (formats/ros_message_decode.hpp) or ROS 2's CDR (formats/ros2_message_decode.hpp), into the same
// structures, so that the import reads every recording alike. What is wrong is a
// ros1::MessageError, as the decoders give it; a topic of another encoding (json, protobuf) is one
// too, naming the encoding.

ros1::PointCloud2 decodePointCloud2(const RecordedMessage& message);
ros1::Imu decodeImu(const RecordedMessage& message);
ros1::StampedPose decodeOdometry(const RecordedMessage& message);
ros1::StampedPose decodePoseStamped(const RecordedMessage& message);
std::vector<ros1::TransformStamped> decodeTfMessage(const RecordedMessage& message);
std::string decodeString(const RecordedMessage& message);
ros1::VelodyneScan decodeVelodyneScan(const RecordedMessage& message);

}  // namespace isg::formats::recorded
