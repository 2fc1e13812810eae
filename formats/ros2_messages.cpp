#include "formats/ros2_messages.hpp"

#include <array>
#include <cstring>
#include <utility>

#include "formats/cdr_writer.hpp"

namespace isg::formats::ros2 {

namespace {

// The .msg texts (fields only), by the name a definition's "MSG:" line gives them.
const std::pair<const char*, const char*> kDefinitions[] = {
    {"builtin_interfaces/Time", "int32 sec\nuint32 nanosec\n"},
    {"std_msgs/Header", "builtin_interfaces/Time stamp\nstring frame_id\n"},
    {"sensor_msgs/PointField",
     "uint8 INT8=1\nuint8 UINT8=2\nuint8 INT16=3\nuint8 UINT16=4\nuint8 INT32=5\nuint8 UINT32=6\n"
     "uint8 FLOAT32=7\nuint8 FLOAT64=8\nstring name\nuint32 offset\nuint8 datatype\n"
     "uint32 count\n"},
    {"sensor_msgs/PointCloud2",
     "std_msgs/Header header\nuint32 height\nuint32 width\nsensor_msgs/PointField[] fields\n"
     "bool is_bigendian\nuint32 point_step\nuint32 row_step\nuint8[] data\nbool is_dense\n"},
    {"geometry_msgs/Quaternion", "float64 x\nfloat64 y\nfloat64 z\nfloat64 w\n"},
    {"geometry_msgs/Vector3", "float64 x\nfloat64 y\nfloat64 z\n"},
    {"geometry_msgs/Point", "float64 x\nfloat64 y\nfloat64 z\n"},
    {"sensor_msgs/Imu",
     "std_msgs/Header header\ngeometry_msgs/Quaternion orientation\n"
     "float64[9] orientation_covariance\ngeometry_msgs/Vector3 angular_velocity\n"
     "float64[9] angular_velocity_covariance\ngeometry_msgs/Vector3 linear_acceleration\n"
     "float64[9] linear_acceleration_covariance\n"},
    {"geometry_msgs/Pose", "geometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n"},
    {"geometry_msgs/PoseWithCovariance", "geometry_msgs/Pose pose\nfloat64[36] covariance\n"},
    {"geometry_msgs/Twist", "geometry_msgs/Vector3 linear\ngeometry_msgs/Vector3 angular\n"},
    {"geometry_msgs/TwistWithCovariance", "geometry_msgs/Twist twist\nfloat64[36] covariance\n"},
    {"nav_msgs/Odometry",
     "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/PoseWithCovariance pose\n"
     "geometry_msgs/TwistWithCovariance twist\n"},
    {"geometry_msgs/Transform",
     "geometry_msgs/Vector3 translation\ngeometry_msgs/Quaternion rotation\n"},
    {"geometry_msgs/TransformStamped",
     "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/Transform transform\n"},
    {"tf2_msgs/TFMessage", "geometry_msgs/TransformStamped[] transforms\n"},
    {"std_msgs/String", "string data\n"},
    {"sensor_msgs/CompressedImage", "std_msgs/Header header\nstring format\nuint8[] data\n"},
    {"sensor_msgs/RegionOfInterest",
     "uint32 x_offset\nuint32 y_offset\nuint32 height\nuint32 width\nbool do_rectify\n"},
    {"sensor_msgs/CameraInfo",
     "std_msgs/Header header\nuint32 height\nuint32 width\nstring distortion_model\n"
     "float64[] d\nfloat64[9] k\nfloat64[9] r\nfloat64[12] p\nuint32 binning_x\n"
     "uint32 binning_y\nsensor_msgs/RegionOfInterest roi\n"},
};

const char* definitionOf(const std::string& name) {
  for (const auto& [type, text] : kDefinitions) {
    if (name == type) return text;
  }
  return "";
}

// The type "package/msg/Type" whose .msg is `top`'s, followed by those of `uses` in order.
MessageType messageType(const std::string& top, std::initializer_list<const char*> uses) {
  MessageType type;
  const std::size_t slash = top.find('/');
  type.name = top.substr(0, slash) + "/msg" + top.substr(slash);
  type.definition = definitionOf(top);
  for (const char* used : uses) {
    type.definition += std::string(80, '=') + "\nMSG: " + used + "\n" + definitionOf(used);
  }
  return type;
}

void writeHeader(CdrWriter& out, Time stamp, const std::string& frame) {
  out.i32(stamp.sec);
  out.u32(stamp.nanosec);
  out.string(frame);
}

void writeVector(CdrWriter& out, const Eigen::Vector3d& v) {
  out.f64(v.x());
  out.f64(v.y());
  out.f64(v.z());
}

void writeQuaternion(CdrWriter& out, const Eigen::Matrix3d& R) {
  Eigen::Quaterniond q(R);
  q.normalize();
  if (q.w() < 0) q.coeffs() = -q.coeffs();  // one of the two, always the same (as the ROS 1 bag)
  out.f64(q.x());
  out.f64(q.y());
  out.f64(q.z());
  out.f64(q.w());
}

template <std::size_t N>
void doubles(CdrWriter& out, const std::array<double, N>& values) {
  for (double v : values) out.f64(v);
}

}  // namespace

MessageType pointCloud2Type() {
  return messageType("sensor_msgs/PointCloud2",
                     {"std_msgs/Header", "builtin_interfaces/Time", "sensor_msgs/PointField"});
}
MessageType imuType() {
  return messageType("sensor_msgs/Imu", {"std_msgs/Header", "builtin_interfaces/Time",
                                         "geometry_msgs/Quaternion", "geometry_msgs/Vector3"});
}
MessageType odometryType() {
  return messageType(
      "nav_msgs/Odometry",
      {"std_msgs/Header", "builtin_interfaces/Time", "geometry_msgs/PoseWithCovariance",
       "geometry_msgs/Pose", "geometry_msgs/Point", "geometry_msgs/Quaternion",
       "geometry_msgs/TwistWithCovariance", "geometry_msgs/Twist", "geometry_msgs/Vector3"});
}
MessageType tfMessageType() {
  return messageType("tf2_msgs/TFMessage", {"geometry_msgs/TransformStamped", "std_msgs/Header",
                                            "builtin_interfaces/Time", "geometry_msgs/Transform",
                                            "geometry_msgs/Vector3", "geometry_msgs/Quaternion"});
}
MessageType stringType() { return messageType("std_msgs/String", {}); }
MessageType compressedImageType() {
  return messageType("sensor_msgs/CompressedImage", {"std_msgs/Header", "builtin_interfaces/Time"});
}
MessageType cameraInfoType() {
  return messageType("sensor_msgs/CameraInfo", {"std_msgs/Header", "builtin_interfaces/Time",
                                                "sensor_msgs/RegionOfInterest"});
}

std::string pointCloud2(const std::vector<sensors::ScanPoint>& points, Time stamp,
                        const std::string& frame, const CloudConvention& convention) {
  const PackedCloud packed = packCloud(points, convention, std::uint32_t(stamp.sec), stamp.nanosec);
  CdrWriter out;
  writeHeader(out, stamp, frame);
  out.u32(1);                             // height
  out.u32(std::uint32_t(points.size()));  // width
  out.u32(std::uint32_t(packed.fields.size()));
  for (const CloudField& f : packed.fields) {
    out.string(f.name);
    out.u32(f.offset);
    out.u8(f.datatype);
    out.u32(1);
  }
  out.boolean(false);  // is_bigendian
  out.u32(packed.point_step);
  out.u32(packed.point_step * std::uint32_t(points.size()));
  out.bytes(packed.data);
  out.boolean(true);  // is_dense: misses are left out, never NaN
  return out.data();
}

std::string imu(const sensors::ImuSample& sample, Time stamp, const std::string& frame,
                double gyroscope_variance, double accelerometer_variance) {
  CdrWriter out;
  writeHeader(out, stamp, frame);
  writeQuaternion(out, Eigen::Matrix3d::Identity());
  std::array<double, 9> covariance{};
  covariance[0] = -1.0;  // no orientation estimate
  doubles(out, covariance);
  writeVector(out, sample.gyroscope);
  covariance = {gyroscope_variance, 0, 0, 0, gyroscope_variance, 0, 0, 0, gyroscope_variance};
  doubles(out, covariance);
  writeVector(out, sample.accelerometer);
  covariance = {accelerometer_variance, 0, 0, 0, accelerometer_variance, 0, 0, 0,
                accelerometer_variance};
  doubles(out, covariance);
  return out.data();
}

std::string odometry(const Eigen::Isometry3d& pose, const Eigen::Vector3d& linear_velocity,
                     const Eigen::Vector3d& angular_velocity, Time stamp, const std::string& frame,
                     const std::string& child) {
  CdrWriter out;
  writeHeader(out, stamp, frame);
  out.string(child);
  writeVector(out, pose.translation());
  writeQuaternion(out, pose.linear());
  doubles(out, std::array<double, 36>{});
  writeVector(out, linear_velocity);
  writeVector(out, angular_velocity);
  doubles(out, std::array<double, 36>{});
  return out.data();
}

std::string tfMessage(const std::vector<StampedTransform>& transforms) {
  CdrWriter out;
  out.u32(std::uint32_t(transforms.size()));
  for (const StampedTransform& t : transforms) {
    writeHeader(out, t.stamp, t.parent);
    out.string(t.child);
    writeVector(out, t.parent_T_child.translation());
    writeQuaternion(out, t.parent_T_child.linear());
  }
  return out.data();
}

std::string stringMessage(const std::string& text) {
  CdrWriter out;
  out.string(text);
  return out.data();
}

std::string compressedImage(const std::string& format, const std::string& data, Time stamp,
                            const std::string& frame) {
  CdrWriter out;
  writeHeader(out, stamp, frame);
  out.string(format);
  out.bytes(data);
  return out.data();
}

std::string cameraInfo(const CameraCalibration& calibration, Time stamp, const std::string& frame) {
  CdrWriter out;
  writeHeader(out, stamp, frame);
  out.u32(std::uint32_t(calibration.height));
  out.u32(std::uint32_t(calibration.width));
  out.string(calibration.distortion_model);
  out.u32(std::uint32_t(calibration.distortion.size()));
  for (double d : calibration.distortion) out.f64(d);
  doubles(out, calibration.K());
  doubles(out, calibration.R());
  doubles(out, calibration.P());
  out.u32(0);                              // binning_x
  out.u32(0);                              // binning_y
  for (int i = 0; i < 4; ++i) out.u32(0);  // roi: x_offset, y_offset, height, width
  out.boolean(false);                      // roi.do_rectify
  return out.data();
}

}  // namespace isg::formats::ros2
