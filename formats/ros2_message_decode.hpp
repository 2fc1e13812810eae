#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "formats/ros_message_decode.hpp"

namespace isg::formats::ros2 {

// ROS 2 messages read back from a recording's CDR bytes (formats/cdr_reader.hpp: either byte
// order), into the same structures as their ROS 1 twins (formats/ros_message_decode.hpp), so that
// the import reads both alike. The differences are the wire's: a std_msgs/Header has no seq and
// its stamp is builtin_interfaces/Time (int32 sec, uint32 nanosec; a stamp before 1970 is
// refused), primitives are aligned, strings and sequences carry uint32 counts. Every length is
// checked before anything is allocated; what is wrong is a ros1::MessageError ("ends inside
// header.frame_id (byte 13 of 20)"), for the caller to name the file, topic and message.

ros1::PointCloud2 decodePointCloud2(std::string_view bytes);
ros1::Imu decodeImu(std::string_view bytes);
ros1::StampedPose decodeOdometry(std::string_view bytes);
ros1::StampedPose decodePoseStamped(std::string_view bytes);
std::vector<ros1::TransformStamped> decodeTfMessage(std::string_view bytes);
std::string decodeString(std::string_view bytes);
// velodyne_msgs/msg/VelodyneScan: a std_msgs/Header, then a sequence of VelodynePacket
// {builtin_interfaces/Time stamp, uint8[1206] data}.
ros1::VelodyneScan decodeVelodyneScan(std::string_view bytes);

}  // namespace isg::formats::ros2
