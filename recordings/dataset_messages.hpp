#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "formats/dataset_reader.hpp"
#include "formats/driver_point_cloud.hpp"
#include "formats/euroc_cameras.hpp"

namespace isg::recordings {

// Topics and frames of an exported dataset, the same in a ROS 1 bag and an MCAP file
// (docs/formats.md, "ROS bags" and "MCAP").
namespace rosbag_names {
inline constexpr const char* kCloudTopic = "/velodyne_points";
inline constexpr const char* kImuTopic = "/imu/data";
inline constexpr const char* kOdometryTopic = "/odom";
inline constexpr const char* kTfTopic = "/tf";
inline constexpr const char* kTfStaticTopic = "/tf_static";
inline constexpr const char* kGroundTruthTopic = "/ground_truth";
// The dataset's metadata.json (sensor model, driver conventions, noise, mounts) as one latched
// std_msgs/String, without its PCD encoding: what a reader of the bag needs to know how it was
// made.
inline constexpr const char* kMetadataTopic = "/isg/metadata";
inline constexpr const char* kPlanFrame = "plan";       // B
inline constexpr const char* kOdometryFrame = "odom";   // M
inline constexpr const char* kBaseFrame = "base_link";  // R
inline constexpr const char* kLidarFrame = "velodyne";  // L
inline constexpr const char* kImuFrame = "imu";         // I
// A camera of the dataset's EuRoC folder (docs/formats.md, "Cameras in bags"): its frame is
// its folder's name ("cam0", "depth0"; optical: z forward, x right, y down), its images on
// /<name>/image_raw/compressed with the calibration on /<name>/camera_info, as the floor-plan
// benchmark's bags and image_transport name them.
inline std::string imageTopic(const std::string& camera) {
  return "/" + camera + "/image_raw/compressed";
}
inline std::string cameraInfoTopic(const std::string& camera) {
  return "/" + camera + "/camera_info";
}
// CompressedImage.format as image_transport's compressed plugin writes it: RGB frames as JPEG
// (decoded to bgr8 by OpenCV), depth as the 16-bit PNG it is stored in (lossless).
inline constexpr const char* kJpegFormat = "rgb8; jpeg compressed bgr8";
inline constexpr const char* kDepthPngFormat = "16UC1; png compressed ";
}  // namespace rosbag_names

// The twist of a body between two poses of it, in the body's frame: the backward difference,
// which is what an odometry source knows at the later time.
struct BodyTwist {
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();
};

// Per-sample variances of an IMU's discretised white noise (density² × rate, from metadata.json's
// imu noise model; 0 without one): the diagonal covariances an Imu message carries.
struct ImuVariances {
  double gyroscope = 0.0;      // (rad/s)²
  double accelerometer = 0.0;  // (m/s²)²
};

// One camera frame as it goes into a bag: the compressed image (format as image_transport's).
struct CameraImage {
  const formats::EurocCamera* camera = nullptr;
  std::string format;
  std::string data;
};

// What an exporter writes of a dataset, called in time order (ties: mounts and metadata, then
// odometry, IMU, scans, camera frames, ground truth).
class DatasetMessageVisitor {
 public:
  virtual ~DatasetMessageVisitor() = default;
  // Once, at the first message's time: the sensors' mounts on base_link and the metadata text
  // (metadata.json without its PCD encoding: the same whichever encoding the dataset has).
  virtual void mounts(
      double t, const std::vector<std::pair<std::string, Eigen::Isometry3d>>& base_link_T_sensor,
      const std::string& metadata) = 0;
  // Odometry pose i of base_link in odom, with its twist.
  virtual void odometry(int i, double t, const Eigen::Isometry3d& pose, const BodyTwist& twist) = 0;
  virtual void imu(int i, double t, const sensors::ImuSample& sample,
                   const ImuVariances& variances) = 0;
  virtual void cloud(int i, double t, const sensors::Scan& scan) = 0;
  // Frame i of a camera, `camera_index` into the cameras given to visitDatasetMessages.
  virtual void image(int camera_index, int i, double t, const CameraImage& image) = 0;
  // Ground-truth pose i of base_link in the plan frame, with its twist.
  virtual void groundTruth(int i, double t, const Eigen::Isometry3d& pose,
                           const BodyTwist& twist) = 0;
};

// What an export wrote.
struct ExportSummary {
  std::map<std::string, std::uint64_t> messages;  // per topic
  std::string cloud_layout;                       // "the Velodyne driver's (x y z …)"
  std::uint64_t bytes = 0;
  double dataset_seconds = 0.0;  // robot time covered
  double wall_seconds = 0.0;
};

// The layout an export writes the clouds in (docs/formats.md, "ROS bags"): the ROS
// driver's of the dataset's LiDAR model (metadata.json lidar.scenario_model: Hesai's for
// pandar-xt32, ouster-ros's for the OS models, Velodyne's for the VLP models), the Velodyne
// driver's when the model is none the simulator knows (an imported recording's, whose rings are
// already by elevation) or `velodyne_layout` asks for it.
formats::CloudConvention exportCloudConvention(const formats::DatasetReader& dataset,
                                               bool velodyne_layout);
// "Ouster's (ouster-ros: x y z intensity t reflectivity ring ambient range, ring 0 = top)", …
std::string describeCloudConvention(const formats::CloudConvention& convention);

// Walks the dataset's messages in time order through `visitor`, with the frames of `cameras`
// (formats::readEurocCameras: RGB frames encoded as JPEG one at a time, depth PNG files as they
// are) and their mounts on base_link; `progress(done, total)` (if set) after each scan and frame.
void visitDatasetMessages(formats::DatasetReader& dataset,
                          const std::vector<formats::EurocCamera>& cameras,
                          DatasetMessageVisitor& visitor,
                          const std::function<void(int, int)>& progress);

}  // namespace isg::recordings
