#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/camera_calibration.hpp"
#include "formats/driver_point_cloud.hpp"
#include "formats/rosbag_writer.hpp"
#include "sensors/messages.hpp"

namespace isg::formats::ros1 {

// ROS 1 messages serialised with Debian's message headers (sensor_msgs, nav_msgs, tf2_msgs over
// roscpp_serialization). Those headers predate C++20 (std::allocator<void>::rebind), so they are
// included only by ros_messages.cpp, compiled as C++17; this interface has none of their types.

RosMessageType pointCloud2Type();
RosMessageType imuType();
RosMessageType odometryType();
RosMessageType tfMessageType();
RosMessageType stringType();
RosMessageType poseStampedType();  // read from recordings, never written
RosMessageType compressedImageType();
RosMessageType cameraInfoType();

// sensor_msgs/PointCloud2 in `convention`'s driver layout (formats/driver_point_cloud.hpp; the
// Velodyne driver's by default: x y z intensity ring time, point_step 22), height 1, dense.
std::string pointCloud2(const std::vector<sensors::ScanPoint>& points, RosTime stamp,
                        std::uint32_t seq, const std::string& frame,
                        const CloudConvention& convention = {});

// sensor_msgs/Imu: no orientation (orientation_covariance[0] = -1, as the message documents for
// a unit without one), rates and specific force with diagonal covariances (per-axis variances).
std::string imu(const sensors::ImuSample& sample, RosTime stamp, std::uint32_t seq,
                const std::string& frame, double gyroscope_variance, double accelerometer_variance);

// nav_msgs/Odometry: `pose` of `child` in `frame`; the twist in `child` (as the message defines).
std::string odometry(const Eigen::Isometry3d& pose, const Eigen::Vector3d& linear_velocity,
                     const Eigen::Vector3d& angular_velocity, RosTime stamp, std::uint32_t seq,
                     const std::string& frame, const std::string& child);

struct StampedTransform {
  RosTime stamp;
  std::string parent, child;
  Eigen::Isometry3d parent_T_child = Eigen::Isometry3d::Identity();
};
// tf2_msgs/TFMessage.
std::string tfMessage(const std::vector<StampedTransform>& transforms);

// std_msgs/String.
std::string stringMessage(const std::string& text);

// sensor_msgs/CompressedImage: `data` as it is, `format` in image_transport's words ("rgb8; jpeg
// compressed bgr8", "16UC1; png compressed ").
std::string compressedImage(const std::string& format, const std::string& data, RosTime stamp,
                            std::uint32_t seq, const std::string& frame);

// sensor_msgs/CameraInfo of an unrectified camera (R the identity, no binning, no region).
std::string cameraInfo(const CameraCalibration& calibration, RosTime stamp, std::uint32_t seq,
                       const std::string& frame);

}  // namespace isg::formats::ros1
