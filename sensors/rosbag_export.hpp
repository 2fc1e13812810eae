#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>

namespace isg::sensors {

// Topics and frames of an exported bag (docs/formats.md, "ROS bags").
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
}  // namespace rosbag_names

struct RosbagExportOptions {
  // Whole seconds added to every dataset time: ROS reads a zero stamp as "no time" (tf's
  // "latest"), so dataset time 0 becomes 1000000000 s (2001-09-09), and bag time T is dataset
  // time T − 1e9.
  std::uint32_t stamp_offset = 1000000000;
  bool overwrite = false;
};

struct RosbagSummary {
  std::map<std::string, std::uint64_t> messages;  // per topic
  std::uint64_t bytes = 0;
  double dataset_seconds = 0.0;  // robot time covered
  double wall_seconds = 0.0;
};

// Writes a dataset folder (docs/formats.md, "Datasets") as a ROS 1 bag: every scan, IMU sample,
// odometry and ground-truth pose, and the transforms between the frames. `progress(done, total)`
// is called after each scan. Bad input is an InputError naming the file; the bag appears at
// `bag_path` only when complete.
RosbagSummary exportRosbag(const std::string& dataset_dir, const std::string& bag_path,
                           const RosbagExportOptions& options,
                           const std::function<void(int, int)>& progress);

}  // namespace isg::sensors
