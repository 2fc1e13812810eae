#include "formats/ros_messages.hpp"

#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/serialization.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_msgs/String.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <cstring>

namespace isg::formats::ros1 {

namespace {

template <typename Message>
RosMessageType typeOf() {
  return {ros::message_traits::DataType<Message>::value(),
          ros::message_traits::MD5Sum<Message>::value(),
          ros::message_traits::Definition<Message>::value()};
}

template <typename Message>
std::string serialise(const Message& message) {
  const std::uint32_t size = ros::serialization::serializationLength(message);
  std::string out(size, '\0');
  ros::serialization::OStream stream(reinterpret_cast<std::uint8_t*>(out.data()), size);
  ros::serialization::serialize(stream, message);
  return out;
}

ros::Time rosTime(RosTime t) { return ros::Time(t.sec, t.nsec); }

std_msgs::Header header(RosTime stamp, std::uint32_t seq, const std::string& frame) {
  std_msgs::Header h;
  h.seq = seq;
  h.stamp = rosTime(stamp);
  h.frame_id = frame;
  return h;
}

geometry_msgs::Quaternion quaternion(const Eigen::Matrix3d& R) {
  Eigen::Quaterniond q(R);
  q.normalize();
  if (q.w() < 0) q.coeffs() = -q.coeffs();  // one of the two, always the same
  geometry_msgs::Quaternion out;
  out.x = q.x();
  out.y = q.y();
  out.z = q.z();
  out.w = q.w();
  return out;
}

geometry_msgs::Vector3 vector(const Eigen::Vector3d& v) {
  geometry_msgs::Vector3 out;
  out.x = v.x();
  out.y = v.y();
  out.z = v.z();
  return out;
}

sensor_msgs::PointField pointField(const char* name, std::uint32_t offset, std::uint8_t type) {
  sensor_msgs::PointField f;
  f.name = name;
  f.offset = offset;
  f.datatype = type;
  f.count = 1;
  return f;
}

}  // namespace

RosMessageType pointCloud2Type() { return typeOf<sensor_msgs::PointCloud2>(); }
RosMessageType imuType() { return typeOf<sensor_msgs::Imu>(); }
RosMessageType odometryType() { return typeOf<nav_msgs::Odometry>(); }
RosMessageType tfMessageType() { return typeOf<tf2_msgs::TFMessage>(); }
RosMessageType stringType() { return typeOf<std_msgs::String>(); }
RosMessageType poseStampedType() { return typeOf<geometry_msgs::PoseStamped>(); }
RosMessageType compressedImageType() { return typeOf<sensor_msgs::CompressedImage>(); }
RosMessageType cameraInfoType() { return typeOf<sensor_msgs::CameraInfo>(); }

std::string compressedImage(const std::string& format, const std::string& data, RosTime stamp,
                            std::uint32_t seq, const std::string& frame) {
  sensor_msgs::CompressedImage message;
  message.header = header(stamp, seq, frame);
  message.format = format;
  message.data.assign(data.begin(), data.end());
  return serialise(message);
}

std::string cameraInfo(const CameraCalibration& calibration, RosTime stamp, std::uint32_t seq,
                       const std::string& frame) {
  sensor_msgs::CameraInfo message;
  message.header = header(stamp, seq, frame);
  message.width = std::uint32_t(calibration.width);
  message.height = std::uint32_t(calibration.height);
  message.distortion_model = calibration.distortion_model;
  message.D = calibration.distortion;
  const auto K = calibration.K(), R = calibration.R();
  const auto P = calibration.P();
  std::copy(K.begin(), K.end(), message.K.begin());
  std::copy(R.begin(), R.end(), message.R.begin());
  std::copy(P.begin(), P.end(), message.P.begin());
  return serialise(message);
}

std::string stringMessage(const std::string& text) {
  std_msgs::String message;
  message.data = text;
  return serialise(message);
}

std::string pointCloud2(const std::vector<sensors::ScanPoint>& points, RosTime stamp,
                        std::uint32_t seq, const std::string& frame,
                        const CloudConvention& convention) {
  PackedCloud packed = packCloud(points, convention, stamp.sec, stamp.nsec);
  sensor_msgs::PointCloud2 cloud;
  cloud.header = header(stamp, seq, frame);
  cloud.height = 1;
  cloud.width = std::uint32_t(points.size());
  for (const CloudField& f : packed.fields)
    cloud.fields.push_back(pointField(f.name, f.offset, f.datatype));
  cloud.is_bigendian = false;
  cloud.point_step = packed.point_step;
  cloud.row_step = packed.point_step * cloud.width;
  cloud.data.assign(packed.data.begin(), packed.data.end());
  cloud.is_dense = true;  // every point is a return: misses are left out, never NaN
  return serialise(cloud);
}

std::string imu(const sensors::ImuSample& sample, RosTime stamp, std::uint32_t seq,
                const std::string& frame, double gyroscope_variance,
                double accelerometer_variance) {
  sensor_msgs::Imu message;
  message.header = header(stamp, seq, frame);
  message.orientation.w = 1.0;
  message.orientation_covariance[0] = -1.0;  // no orientation estimate
  message.angular_velocity = vector(sample.gyroscope);
  message.linear_acceleration = vector(sample.accelerometer);
  for (int i = 0; i < 3; ++i) {
    message.angular_velocity_covariance[4 * i] = gyroscope_variance;
    message.linear_acceleration_covariance[4 * i] = accelerometer_variance;
  }
  return serialise(message);
}

std::string odometry(const Eigen::Isometry3d& pose, const Eigen::Vector3d& linear_velocity,
                     const Eigen::Vector3d& angular_velocity, RosTime stamp, std::uint32_t seq,
                     const std::string& frame, const std::string& child) {
  nav_msgs::Odometry message;
  message.header = header(stamp, seq, frame);
  message.child_frame_id = child;
  message.pose.pose.position.x = pose.translation().x();
  message.pose.pose.position.y = pose.translation().y();
  message.pose.pose.position.z = pose.translation().z();
  message.pose.pose.orientation = quaternion(pose.linear());
  message.twist.twist.linear = vector(linear_velocity);
  message.twist.twist.angular = vector(angular_velocity);
  return serialise(message);
}

std::string tfMessage(const std::vector<StampedTransform>& transforms) {
  tf2_msgs::TFMessage message;
  for (const StampedTransform& t : transforms) {
    geometry_msgs::TransformStamped out;
    out.header.stamp = rosTime(t.stamp);
    out.header.frame_id = t.parent;
    out.child_frame_id = t.child;
    out.transform.translation = vector(t.parent_T_child.translation());
    out.transform.rotation = quaternion(t.parent_T_child.linear());
    message.transforms.push_back(out);
  }
  return serialise(message);
}

}  // namespace isg::formats::ros1
