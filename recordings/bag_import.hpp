#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace isg::recordings {

// Which topic plays which part, and what the recording does not say (docs/formats.md, "Importing
// recordings").
struct BagImportOptions {
  // Empty: found by type (and, for odometry against ground truth, by name) when unambiguous.
  // "none" (IMU, odometry, ground truth): leave that stream out.
  // The odometry topic may also be a tf topic (/tf): the odometry is then the chain of its
  // transforms from the odometry's frame down to the base.
  std::string lidar_topic, imu_topic, odometry_topic, ground_truth_topic;
  // The odometry's fixed frame on /tf (default: the frame above the LiDAR named odom…).
  std::string odometry_frame;
  // The part of the recording to import: seconds after its first message, and how long.
  double start = 0.0;
  std::optional<double> duration;
  // The robot's base frame R (default: the odometry's child frame — on /tf, the frame the link
  // nearest the LiDAR moves; without odometry, the ground truth's child frame when the fixed
  // frames join it to the LiDAR, else the LiDAR's own frame: a handheld sensor).
  std::string base_frame;
  // R_T_L and R_T_I as x y z (m) roll pitch yaw (rad), when /tf_static does not join the frames.
  std::optional<std::array<double, 6>> lidar_extrinsic, imu_extrinsic;
  bool overwrite = false;
};

struct BagImportSummary {
  struct Stream {
    std::string topic, type;
    std::uint64_t messages = 0;  // imported
  };
  Stream lidar, imu, odometry, ground_truth;  // topic empty: not imported
  std::string cloud_layout;                   // CloudLayout::describe()
  std::string stamp;                          // "first_firing" or "last_packet"
  std::string odometry_chain;                 // odometry from /tf: its frames (TfOdometry)
  std::array<double, 2> point_time{0.0, 0.0};
  double scan_period = 0.0;
  double seconds = 0.0;            // robot time the dataset covers
  std::uint64_t points = 0;        // in all scans
  bool from_isg = false;           // the bag carries an isg dataset's metadata
  std::vector<std::string> notes;  // what was left out or assumed, one line each
};

// Reads a ROS 1 bag (sensors/rosbag_reader.hpp) and writes the dataset folder `dataset_dir`
// (docs/formats.md, "Datasets") all at once: scans/ from the point clouds, imu.csv, odometry.tum,
// groundtruth.tum and scans.tum when there is ground truth (scans.txt, stamps only, when there is
// none), metadata.json. Times are seconds from the whole second at or before the first imported
// stamp. A bag written by `isg export` carries its dataset's metadata and imports back to that
// dataset. `progress(done, total)` counts the clouds. Errors are InputErrors naming the bag, the
// topic, the message's index on it and what is wrong; nothing is left half-written.
BagImportSummary importRosbag(const std::string& bag_path, const std::string& dataset_dir,
                              const BagImportOptions& options,
                              const std::function<void(std::uint64_t, std::uint64_t)>& progress);

}  // namespace isg::recordings
