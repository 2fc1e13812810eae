#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/camera_calibration.hpp"
#include "formats/driver_point_cloud.hpp"
#include "sensors/messages.hpp"

namespace isg::formats::ros2 {

// ROS 2 messages in CDR (sensors/cdr_writer.hpp), the same content as the ROS 1 bag's
// (sensors/ros_messages.hpp) but for ROS 2's header, which has no seq.

// builtin_interfaces/Time.
struct Time {
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;
  std::uint64_t nanoseconds() const { return std::uint64_t(sec) * 1000000000ull + nanosec; }
};

// A message type as an MCAP file declares it: its name ("sensor_msgs/msg/Imu") and its
// definition in the ros2msg encoding (the .msg text, then each type it uses after a line of 80
// '=' and "MSG: package/Type").
struct MessageType {
  std::string name;
  std::string definition;
};

MessageType pointCloud2Type();
MessageType imuType();
MessageType odometryType();
MessageType tfMessageType();
MessageType stringType();
MessageType compressedImageType();
MessageType cameraInfoType();

// sensor_msgs/msg/PointCloud2 in `convention`'s driver layout (formats/driver_point_cloud.hpp;
// the Velodyne driver's by default: x y z intensity ring time, point_step 22), height 1, dense.
std::string pointCloud2(const std::vector<sensors::ScanPoint>& points, Time stamp,
                        const std::string& frame, const CloudConvention& convention = {});
// sensor_msgs/msg/Imu: no orientation (orientation_covariance[0] = -1), diagonal covariances.
std::string imu(const sensors::ImuSample& sample, Time stamp, const std::string& frame,
                double gyroscope_variance, double accelerometer_variance);
// nav_msgs/msg/Odometry: `pose` of `child` in `frame`, the twist in `child`.
std::string odometry(const Eigen::Isometry3d& pose, const Eigen::Vector3d& linear_velocity,
                     const Eigen::Vector3d& angular_velocity, Time stamp, const std::string& frame,
                     const std::string& child);
struct StampedTransform {
  Time stamp;
  std::string parent, child;
  Eigen::Isometry3d parent_T_child = Eigen::Isometry3d::Identity();
};
// tf2_msgs/msg/TFMessage.
std::string tfMessage(const std::vector<StampedTransform>& transforms);
// std_msgs/msg/String.
std::string stringMessage(const std::string& text);

// sensor_msgs/msg/CompressedImage, as the ROS 1 bag's (formats/ros_messages.hpp).
std::string compressedImage(const std::string& format, const std::string& data, Time stamp,
                            const std::string& frame);

// sensor_msgs/msg/CameraInfo of an unrectified camera, as the ROS 1 bag's.
std::string cameraInfo(const CameraCalibration& calibration, Time stamp, const std::string& frame);

}  // namespace isg::formats::ros2
