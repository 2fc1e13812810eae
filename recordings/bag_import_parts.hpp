#pragma once

// The ROS bag import's own parts (recordings/bag_import.hpp is its interface): the Import that
// holds what a recording's import reads, with its steps in files of their own —
// recordings/topic_choice.cpp (which topics are the LiDAR, the IMU, the odometry, the ground
// truth), recordings/frame_resolution.cpp (the sensors' mounts and the odometry's frames, from
// /tf_static and /tf), recordings/stream_reading.cpp (the messages read, the scans written) and
// recordings/dataset_writer.cpp (the dataset's other files and its metadata). Included only by
// those files.

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>

#include "common/atomic_folder.hpp"
#include "common/input_error.hpp"
#include "common/plural.hpp"
#include "common/pose_interpolation.hpp"
#include "common/version.hpp"
#include "formats/cloud_layout.hpp"
#include "formats/dataset_format.hpp"
#include "formats/dataset_metadata.hpp"
#include "formats/recorded_message_decode.hpp"
#include "formats/recording.hpp"
#include "formats/ros_message_decode.hpp"
#include "formats/ros_messages.hpp"
#include "formats/vlp16_packet.hpp"
#include "formats/vlp16_turns.hpp"
#include "recordings/bag_import.hpp"
#include "recordings/rosbag_export.hpp"
#include "recordings/static_frames.hpp"
#include "recordings/tf_odometry.hpp"
#include "sensors/mount_transform.hpp"

namespace isg::recordings::bag_import {

namespace fs = std::filesystem;

inline constexpr const char* kNone = "none";
inline constexpr const char* kCloudType = "sensor_msgs/PointCloud2";
inline constexpr const char* kVelodyneScanType = "velodyne_msgs/VelodyneScan";  // raw packets
inline constexpr const char* kImuType = "sensor_msgs/Imu";
inline constexpr const char* kOdometryType = "nav_msgs/Odometry";
inline constexpr const char* kPoseType = "geometry_msgs/PoseStamped";
inline constexpr const char* kStringType = "std_msgs/String";
inline constexpr const char* kTfType = "tf2_msgs/TFMessage";
inline constexpr const char* kOldTfType = "tf/tfMessage";  // ROS 1's first tf: the same definition
// An IMU whose specific force at rest has a norm within this of 1 reports it in g (Livox's, some
// MEMS drivers), not m/s²: 0.2 g is far from both 1 m/s² and 9.81 m/s².
inline constexpr double kGravityInG = 0.2;
inline constexpr double kStandardGravity = 9.80665;

// A topic of the bag: its connections merged (one topic may have several publishers).
// `datatype` is in ROS 1's spelling whichever ROS recorded it; `recorded_type` as recorded.
struct Topic {
  std::string name, datatype, md5sum, recorded_type;
  formats::MessageEncoding encoding = formats::MessageEncoding::kRos1;
  std::string encoding_name;
  std::uint64_t messages = 0;
};

std::string lower(std::string text);

// A ground-truth topic by its name: a name part (between '/' and '_') "gt", or the words
// ground_truth, groundtruth, vicon, mocap.
bool namedLikeGroundTruth(const std::string& topic);

// A LiDAR driver's raw packets (or its own point format) rather than sensor_msgs/PointCloud2:
// the packet and scan messages of the Velodyne, Ouster, Hesai, Robosense and Livox drivers, and
// any type whose name says packet.
bool isRawLidarType(const std::string& datatype);

bool isTfType(const std::string& datatype);

bool isStaticTfTopic(const std::string& name);

// A transform that closes a cycle of frames: tf's frames form a tree, and tf itself refuses the
// lookup through one, so the import refuses it too rather than drop a link unsaid.
std::string cycleMessage(const std::string& parent, const std::string& child,
                         const std::string& cycle);

class Import {
 public:
  Import(const std::string& bag_path, const BagImportOptions& options)
      : bag_path_(bag_path), options_(options), bag_(formats::openRecording(bag_path)) {}

  BagImportSummary run(const fs::path& folder,
                       const std::function<void(std::uint64_t, std::uint64_t)>& progress);

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw common::InputError(bag_path_, "", what);
  }
  // A message's error: its topic, its index on it, and where the recording keeps it when it
  // says (an SQLite row, an MCAP record's byte: formats::placeOf).
  [[noreturn]] void failMessage(const std::string& topic, std::uint64_t index,
                                const std::string& what,
                                const formats::RecordedMessage* message = nullptr) const {
    const std::string place = message ? formats::placeOf(*message) : "";
    fail("topic " + topic + ", message " + std::to_string(index) +
         (place.empty() ? "" : " (" + place + ")") + ": " + what);
  }
  void collectTopics();
  std::string listing(const std::vector<const Topic*>& topics) const;
  const Topic* findTopic(const std::string& name) const;
  std::string chooseTopic(const char* role, const char* flag, const std::string& option,
                          const std::vector<std::string>& types,
                          const std::function<bool(const Topic&)>& preferred, bool required);
  void chooseTopics();
  void readStatic();
  // The first message on `topic` (any time) decoded, for its frames before the long read; a
  // message error names the message.
  template <class Decode>
  auto decodeFirst(const std::string& topic, Decode decode);
  void resolveFrames();
  // The odometry as a chain of /tf: its frames from the whole topic; false (and the odometry left
  // out) when the topic was not asked for and no frame above the LiDAR is named as odometry.
  bool resolveTfOdometry();
  // The transforms on /tf as a tree; links that never change taken as fixed frames (noted).
  MovingFrameTree readTfTree();
  // The base frame among the frames above the LiDAR's, up to the odometry's (at `top`).
  std::string baseBelow(const std::vector<MovingFrameTree::Above>& above, std::ptrdiff_t top) const;
  Eigen::Isometry3d mount(const char* sensor, const char* flag, const std::string& frame,
                          const std::optional<std::array<double, 6>>& option);
  // child_T_R for a pose stream whose child frame is `child`.
  Eigen::Isometry3d childToBase(const std::string& topic, const std::string& child);
  void readStreams(const fs::path& folder,
                   const std::function<void(std::uint64_t, std::uint64_t)>& progress);
  double seconds(formats::RosTime t) const {
    return double(std::int64_t(t.sec) - std::int64_t(origin_)) + 1e-9 * t.nsec;
  }
  void writeFiles(const fs::path& folder);
  // One message of each stream, checked against the stream's first (frame, layout, stamps in
  // order); a bad one throws formats::ros1::MessageError. A cloud is written as its scan file.
  void readCloud(const fs::path& folder, const formats::RecordedMessage& m);
  // A VelodyneScan's packets decoded (formats/vlp16_packet.hpp) and cut into turns at azimuth 0;
  // each turn the packets complete is written as a scan stamped at its first firing.
  void readPackets(const fs::path& folder, const formats::RecordedMessage& m, std::uint64_t index);
  // One scan file, its stamp and its points' times (`timed`: the points carry them).
  void writeScan(const fs::path& folder, formats::RosTime stamp,
                 const std::vector<sensors::ScanPoint>& points, bool timed);
  void readImu(const formats::RecordedMessage& m);
  void readPose(const formats::RecordedMessage& m);
  // The odometry the transforms on /tf make, when the bag's odometry is that.
  void takeTfOdometry();
  // The IMU's samples in dataset time, in m/s² (a driver's g converted, and said).
  std::vector<sensors::ImuSample> imuInDatasetTime();
  // The scans' stamps in dataset time within the odometry's span; the scan files outside it
  // removed, the others renumbered from 0.
  std::vector<double> scansWithinOdometry(const fs::path& folder,
                                          const common::Trajectory& odometry);
  // scans.tum (the ground truth covers every scan), else scans.txt.
  void writeScanTimes(const fs::path& folder, const std::vector<double>& stamps,
                      const common::Trajectory& truth);
  // metadata.json: an isg dataset's own back, or metadata(); and where it was imported from.
  nlohmann::ordered_json datasetMetadata(const std::vector<double>& stamps,
                                         const std::vector<sensors::ImuSample>& imu,
                                         const common::Trajectory& odometry);
  // The metadata of a recording isg did not write, as far as its frames go.
  // metadata.json of a recording (not an isg dataset's): what was imported, as every dataset
  // says it, and which topics and frames it came from.
  nlohmann::ordered_json metadata(const std::vector<double>& stamps,
                                  const std::vector<sensors::ImuSample>& imu,
                                  const common::Trajectory& odometry) const;

  std::string bag_path_;
  BagImportOptions options_;
  std::unique_ptr<formats::Recording> bag_;
  std::vector<Topic> topics_;
  BagImportSummary summary_;
  StaticFrames frames_;
  std::optional<nlohmann::json> isg_metadata_;
  // Odometry from /tf: the topic (asked for with --odom-topic, or the one looked into when the
  // bag has no nav_msgs/Odometry), then the chain once its frames are known.
  std::string tf_topic_;
  bool tf_asked_ = false;
  std::optional<TfOdometry> tf_odometry_;

  // What was read, stamps as the bag has them.
  std::vector<formats::RosTime> scan_stamps_;
  std::string lidar_frame_, imu_frame_, base_frame_, odometry_frame_, truth_frame_;
  formats::CloudLayout layout_;
  // Raw packets: the returns of the turn under way (times from packet_origin_ s), and how many
  // turns were cut short or echoes left out.
  bool packets_ = false;
  std::vector<formats::Vlp16Point> turn_points_;
  std::uint32_t packet_origin_ = 0;
  bool packet_turns_started_ = false;
  std::uint64_t packet_count_ = 0, weak_echoes_ = 0;
  formats::Vlp16ReturnMode packet_mode_ = formats::Vlp16ReturnMode::kStrongest;
  struct TimedSample {
    formats::RosTime stamp;
    sensors::ImuSample sample;
  };
  std::vector<TimedSample> imu_;
  std::array<double, 2> imu_variance_{0.0, 0.0};  // gyroscope, accelerometer; 0: not given
  struct TimedPose {
    formats::RosTime stamp;
    Eigen::Isometry3d pose;
  };
  std::vector<TimedPose> odometry_, truth_;
  std::string odometry_child_, truth_child_;
  double time_min_ = 0.0, time_max_ = 0.0;
  std::uint64_t clouds_with_time_ = 0, clouds_stamped_at_end_ = 0;
  std::vector<std::uint16_t> ring_order_;  // the recording's ring → the dataset's (empty: as is)
  bool ring_order_decided_ = false;
  std::uint32_t origin_ = 0;
  Eigen::Isometry3d R_T_L_ = Eigen::Isometry3d::Identity(), R_T_I_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d odometry_C_T_R_ = Eigen::Isometry3d::Identity(),
                    truth_C_T_R_ = Eigen::Isometry3d::Identity();
};

}  // namespace isg::recordings::bag_import
