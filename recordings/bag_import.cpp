#include "recordings/bag_import.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
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
#include "recordings/rosbag_export.hpp"
#include "recordings/static_frames.hpp"
#include "recordings/tf_odometry.hpp"
#include "sensors/mount_transform.hpp"

namespace isg::recordings {

namespace fs = std::filesystem;

namespace {

constexpr const char* kNone = "none";
constexpr const char* kCloudType = "sensor_msgs/PointCloud2";
constexpr const char* kVelodyneScanType = "velodyne_msgs/VelodyneScan";  // raw packets
constexpr const char* kImuType = "sensor_msgs/Imu";
constexpr const char* kOdometryType = "nav_msgs/Odometry";
constexpr const char* kPoseType = "geometry_msgs/PoseStamped";
constexpr const char* kStringType = "std_msgs/String";
constexpr const char* kTfType = "tf2_msgs/TFMessage";
constexpr const char* kOldTfType = "tf/tfMessage";  // ROS 1's first tf: the same definition
// An IMU whose specific force at rest has a norm within this of 1 reports it in g (Livox's, some
// MEMS drivers), not m/s²: 0.2 g is far from both 1 m/s² and 9.81 m/s².
constexpr double kGravityInG = 0.2;
constexpr double kStandardGravity = 9.80665;

// A topic of the bag: its connections merged (one topic may have several publishers).
// `datatype` is in ROS 1's spelling whichever ROS recorded it; `recorded_type` as recorded.
struct Topic {
  std::string name, datatype, md5sum, recorded_type;
  formats::MessageEncoding encoding = formats::MessageEncoding::kRos1;
  std::string encoding_name;
  std::uint64_t messages = 0;
};

std::string lower(std::string text) {
  for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

// A ground-truth topic by its name: a name part (between '/' and '_') "gt", or the words
// ground_truth, groundtruth, vicon, mocap.
bool namedLikeGroundTruth(const std::string& topic) {
  const std::string name = lower(topic);
  for (const char* word : {"ground_truth", "groundtruth", "vicon", "mocap"}) {
    if (name.find(word) != std::string::npos) return true;
  }
  std::string part;
  for (char c : name + "/") {
    if (c == '/' || c == '_') {
      if (part == "gt") return true;
      part.clear();
    } else {
      part += c;
    }
  }
  return false;
}

// A LiDAR driver's raw packets (or its own point format) rather than sensor_msgs/PointCloud2:
// the packet and scan messages of the Velodyne, Ouster, Hesai, Robosense and Livox drivers, and
// any type whose name says packet.
bool isRawLidarType(const std::string& datatype) {
  static constexpr const char* kKnown[] = {
      "velodyne_msgs/VelodyneScan", "hesai_ros_driver/UdpFrame",  "pandar_msgs/PandarScan",
      "rslidar_msgs/rslidarScan",   "livox_ros_driver/CustomMsg", "livox_ros_driver2/CustomMsg",
  };
  for (const char* known : kKnown) {
    if (datatype == known) return true;
  }
  const std::size_t slash = datatype.find('/');
  const std::string name =
      lower(slash == std::string::npos ? datatype : datatype.substr(slash + 1));
  return name.find("packet") != std::string::npos;
}

bool isTfType(const std::string& datatype) { return datatype == kTfType || datatype == kOldTfType; }

bool isStaticTfTopic(const std::string& name) {
  return name.size() >= 9 && name.ends_with("tf_static");
}

// A transform that closes a cycle of frames: tf's frames form a tree, and tf itself refuses the
// lookup through one, so the import refuses it too rather than drop a link unsaid.
std::string cycleMessage(const std::string& parent, const std::string& child,
                         const std::string& cycle) {
  if (parent == child) return "the frame \"" + child + "\" hangs from itself";
  return "the transform \"" + parent + "\" → \"" + child + "\" closes a cycle of frames (" + cycle +
         "); tf's frames form a tree";
}

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

void Import::collectTopics() {
  for (const auto& recorded : bag_->topics()) {
    auto it = std::find_if(topics_.begin(), topics_.end(),
                           [&](const Topic& t) { return t.name == recorded.name; });
    if (it == topics_.end()) {
      topics_.push_back({recorded.name, recorded.type, recorded.md5sum, recorded.recorded_type,
                         recorded.encoding, recorded.encoding_name, 0});
      it = topics_.end() - 1;
    } else if (it->datatype != recorded.type || it->encoding != recorded.encoding) {
      fail("topic " + recorded.name + " carries both " + it->recorded_type + " (" +
           it->encoding_name + ") and " + recorded.recorded_type + " (" + recorded.encoding_name +
           ") (two publishers disagree)");
    }
    it->messages += recorded.messages;
  }
  std::sort(topics_.begin(), topics_.end(),
            [](const Topic& a, const Topic& b) { return a.name < b.name; });
}

std::string Import::listing(const std::vector<const Topic*>& topics) const {
  std::string out;
  for (const Topic* t : topics) {
    out += std::string(out.empty() ? "" : ", ") + t->name + " (" + t->recorded_type + ", " +
           common::counted(t->messages, "message") + ")";
  }
  return out.empty() ? "none" : out;
}

const Topic* Import::findTopic(const std::string& name) const {
  for (const auto& t : topics_) {
    if (t.name == name) return &t;
  }
  return nullptr;
}

std::string Import::chooseTopic(const char* role, const char* flag, const std::string& option,
                                const std::vector<std::string>& types,
                                const std::function<bool(const Topic&)>& preferred, bool required) {
  std::vector<const Topic*> all;
  for (const auto& t : topics_) all.push_back(&t);
  std::string type_list;
  for (const auto& type : types) type_list += (type_list.empty() ? "" : " or ") + type;
  if (option == kNone) {
    if (required) fail(std::string("the ") + role + " cannot be left out (" + flag + " none)");
    return "";
  }
  if (!option.empty()) {
    const Topic* topic = findTopic(option);
    if (!topic) {
      fail(std::string(flag) + " " + option +
           ": the bag has no such topic (its topics: " + listing(all) + ")");
    }
    if (std::find(types.begin(), types.end(), topic->datatype) == types.end()) {
      fail(std::string(flag) + " " + option + ": the topic carries " + topic->recorded_type +
           ", the " + role + " must be " + type_list +
           (isRawLidarType(topic->datatype)
                ? " (a LiDAR's raw packets, which the import does not decode: record the "
                  "driver's point-cloud topic)"
                : ""));
    }
    return option;
  }
  std::vector<const Topic*> candidates;
  for (const auto& t : topics_) {
    if (std::find(types.begin(), types.end(), t.datatype) != types.end() && preferred(t) &&
        t.messages > 0) {
      candidates.push_back(&t);
    }
  }
  if (candidates.size() > 1) {
    fail(std::string("several topics could be the ") + role + ": " + listing(candidates) +
         "; choose one with " + flag);
  }
  if (candidates.empty()) {
    if (!required) return "";
    std::vector<const Topic*> typed, packets;
    for (const auto& t : topics_) {
      if (std::find(types.begin(), types.end(), t.datatype) != types.end()) typed.push_back(&t);
      if (isRawLidarType(t.datatype)) packets.push_back(&t);
    }
    // Topics of the type, but empty: naming another one may help. Of another type: it cannot.
    if (!typed.empty()) {
      fail(std::string("no message on the ") + type_list + " topics for the " + role + " (" +
           listing(typed) + "); name another with " + flag);
    }
    if (std::string(role) == "LiDAR" && !packets.empty()) {
      fail("the bag has no point clouds (" + type_list + "), only a LiDAR's raw packets: " +
           listing(packets) + "; the import reads point clouds and decodes no packet type " +
           "but Velodyne's VLP-16 packets (velodyne_msgs/VelodyneScan): record the driver's " +
           "point-cloud topic, or play the bag through the driver and record its clouds");
    }
    fail(std::string("the bag has no ") + type_list + " topic for the " + role +
         " (its topics: " + listing(all) + ")");
  }
  return candidates[0]->name;
}

void Import::chooseTopics() {
  const auto anything = [](const Topic&) { return true; };
  // The LiDAR: a point-cloud topic; else the Velodyne driver's raw packets, decoded here.
  if (!options_.lidar_topic.empty()) {
    summary_.lidar.topic = chooseTopic("LiDAR", "--lidar-topic", options_.lidar_topic,
                                       {kCloudType, kVelodyneScanType}, anything, true);
  } else {
    for (const char* type : {kCloudType, kVelodyneScanType}) {
      if (summary_.lidar.topic.empty()) {
        summary_.lidar.topic = chooseTopic("LiDAR", "--lidar-topic", "", {type}, anything, false);
      }
    }
    if (summary_.lidar.topic.empty()) {  // says why none could be
      chooseTopic("LiDAR", "--lidar-topic", "", {kCloudType}, anything, true);
    }
  }
  packets_ = findTopic(summary_.lidar.topic)->datatype == kVelodyneScanType;
  summary_.imu.topic =
      chooseTopic("IMU", "--imu-topic", options_.imu_topic, {kImuType}, anything, false);
  // Odometry and ground truth may both be nav_msgs/Odometry: told apart by name, and a topic
  // named for one part is not a candidate for the other.
  summary_.ground_truth.topic = chooseTopic(
      "ground truth", "--ground-truth-topic", options_.ground_truth_topic,
      {kOdometryType, kPoseType},
      [&](const Topic& t) {
        return namedLikeGroundTruth(t.name) && t.name != options_.odometry_topic;
      },
      false);
  // The odometry: a nav_msgs/Odometry topic, or the transforms of a tf topic (named with
  // --odom-topic, or /tf looked into when no odometry topic is there).
  const Topic* named = options_.odometry_topic.empty() || options_.odometry_topic == kNone
                           ? nullptr
                           : findTopic(options_.odometry_topic);
  if (named && isTfType(named->datatype)) {
    if (isStaticTfTopic(named->name)) {
      fail("--odom-topic " + named->name +
           ": fixed frames do not move; name the tf topic whose "
           "transforms move the base (/tf)");
    }
    tf_topic_ = named->name;
    tf_asked_ = true;
  } else {
    summary_.odometry.topic = chooseTopic(
        "odometry", "--odom-topic", options_.odometry_topic, {kOdometryType},
        [&](const Topic& t) {
          return !namedLikeGroundTruth(t.name) && t.name != summary_.ground_truth.topic;
        },
        false);
    if (summary_.odometry.topic.empty() && options_.odometry_topic.empty()) {
      std::vector<const Topic*> moving;
      for (const auto& t : topics_) {
        if (isTfType(t.datatype) && !isStaticTfTopic(t.name) && t.messages > 0) {
          moving.push_back(&t);
        }
      }
      const auto tf = std::find_if(moving.begin(), moving.end(),
                                   [](const Topic* t) { return t->name == "/tf"; });
      if (tf != moving.end()) {
        tf_topic_ = (*tf)->name;
      } else if (moving.size() == 1) {
        tf_topic_ = moving[0]->name;
      }
    }
  }
  if (!options_.odometry_frame.empty() && tf_topic_.empty()) {
    fail("--odom-frame " + options_.odometry_frame +
         (summary_.odometry.topic.empty()
              ? std::string(": the bag has no tf topic to take the odometry from")
              : ": the odometry is " + summary_.odometry.topic +
                    " (nav_msgs/Odometry); --odom-frame names the odometry's frame on /tf"));
  }
  if (!summary_.odometry.topic.empty() && summary_.odometry.topic == summary_.ground_truth.topic) {
    fail("topic " + summary_.odometry.topic + " cannot be both the odometry and the ground truth");
  }
  // A type of another definition than the standard one would be misread: refused by its MD5.
  const std::pair<const char*, formats::RosMessageType> standard[] = {
      {kCloudType, formats::ros1::pointCloud2Type()}, {kImuType, formats::ros1::imuType()},
      {kOdometryType, formats::ros1::odometryType()}, {kPoseType, formats::ros1::poseStampedType()},
      {kTfType, formats::ros1::tfMessageType()},      {kOldTfType, formats::ros1::tfMessageType()}};
  BagImportSummary::Stream tf{tf_topic_, "", 0};
  for (auto* stream :
       {&summary_.lidar, &summary_.imu, &summary_.odometry, &summary_.ground_truth, &tf}) {
    if (stream->topic.empty()) continue;
    const Topic* topic = findTopic(stream->topic);
    stream->type = topic->recorded_type;
    if (topic->encoding == formats::MessageEncoding::kOther) {
      fail("topic " + topic->name + " is encoded as \"" + topic->encoding_name +
           "\": the import reads ROS messages (ros1, or ROS 2's cdr)");
    }
    // ROS 2 and MCAP give no MD5 (md5sum ""): their definitions are taken as the standard ones.
    for (const auto& [name, type] : standard) {
      if (topic->datatype == name && !topic->md5sum.empty() && topic->md5sum != type.md5sum &&
          topic->md5sum != "*") {
        fail("topic " + topic->name + ": its " + name + " has the MD5 sum " + topic->md5sum +
             ", not the standard definition's " + type.md5sum);
      }
    }
  }
}

// The fixed frames from every tf_static topic, and an isg dataset's metadata, whatever the
// window: both are latched once at the start.
void Import::readStatic() {
  std::vector<std::string> static_topics;
  for (const auto& t : topics_) {
    if (isTfType(t.datatype) && isStaticTfTopic(t.name)) {
      static_topics.push_back(t.name);
    }
  }
  std::map<std::string, std::uint64_t> counts;
  if (!static_topics.empty()) {
    bag_->read(static_topics, [&](const formats::RecordedMessage& m) {
      const std::uint64_t index = counts[m.topic->name]++;
      try {
        for (const auto& t : formats::recorded::decodeTfMessage(m)) {
          if (const auto cycle = frames_.cycleIfAdded(t.header.frame_id, t.child_frame_id)) {
            throw formats::ros1::MessageError(
                cycleMessage(t.header.frame_id, t.child_frame_id, *cycle));
          }
          frames_.add(t.header.frame_id, t.child_frame_id, t.parent_T_child);
        }
      } catch (const formats::ros1::MessageError& e) {
        failMessage(m.topic->name, index, e.what(), &m);
      }
      return true;
    });
  }
  const Topic* made = findTopic(rosbag_names::kMetadataTopic);
  if (made && made->datatype == kStringType) {
    bag_->read({made->name}, [&](const formats::RecordedMessage& m) {
      try {
        isg_metadata_ = nlohmann::json::parse(formats::recorded::decodeString(m));
      } catch (const formats::ros1::MessageError& e) {
        failMessage(made->name, 0, e.what());
      } catch (const nlohmann::json::exception& e) {
        failMessage(made->name, 0, std::string("not a dataset's metadata (JSON): ") + e.what());
      }
      if (!isg_metadata_->is_object() ||
          isg_metadata_->value("format", "") != formats::dataset::kFormat) {
        failMessage(made->name, 0, "not an isg dataset's metadata");
      }
      return false;
    });
  }
}

Eigen::Isometry3d Import::mount(const char* sensor, const char* flag, const std::string& frame,
                                const std::optional<std::array<double, 6>>& option) {
  if (option) return sensors::mountTransform(*option);
  if (auto T = frames_.transform(base_frame_, frame)) return *T;
  fail(std::string("no transform from the base frame \"") + base_frame_ + "\" to the " + sensor +
       "'s frame \"" + frame + "\" in /tf_static: give " + flag + " X,Y,Z,ROLL,PITCH,YAW (the " +
       sensor + "'s pose on the base, metres and radians)");
}

Eigen::Isometry3d Import::childToBase(const std::string& topic, const std::string& child) {
  if (child.empty() || child == base_frame_) return Eigen::Isometry3d::Identity();
  if (auto T = frames_.transform(child, base_frame_)) return *T;
  fail("topic " + topic + " gives the pose of \"" + child + "\", and /tf_static has no transform " +
       "from it to the base frame \"" + base_frame_ + "\"");
}

template <class Decode>
auto Import::decodeFirst(const std::string& topic, Decode decode) {
  std::optional<decltype(decode(std::declval<const formats::RecordedMessage&>()))> first;
  bag_->read({topic}, [&](const formats::RecordedMessage& m) {
    try {
      first = decode(m);
    } catch (const formats::ros1::MessageError& e) {
      failMessage(topic, 0, e.what(), &m);
    }
    return false;
  });
  if (!first) failMessage(topic, 0, "the topic has no message");
  return std::move(*first);
}

MovingFrameTree Import::readTfTree() {
  MovingFrameTree tree;
  std::uint64_t index = 0;
  bag_->read({tf_topic_}, [&](const formats::RecordedMessage& m) {
    try {
      for (const auto& t : formats::recorded::decodeTfMessage(m)) {
        if (const auto cycle = tree.cycleIfAdded(t.header.frame_id, t.child_frame_id, frames_)) {
          throw formats::ros1::MessageError(
              cycleMessage(t.header.frame_id, t.child_frame_id, *cycle) +
              (tf_asked_ ? "" : "; --odom-topic none leaves /tf out"));
        }
        if (const auto other = tree.add(t.header.frame_id, t.child_frame_id, t.parent_T_child)) {
          throw formats::ros1::MessageError(
              "the frame \"" + t.child_frame_id + "\" hangs from \"" + t.header.frame_id +
              "\" here and from \"" + *other + "\" before (a frame has one parent)" +
              (tf_asked_ ? "" : "; --odom-topic none leaves /tf out"));
        }
      }
    } catch (const formats::ros1::MessageError& e) {
      failMessage(tf_topic_, index, e.what(), &m);
    }
    ++index;
    return true;
  });
  // Links that never change on /tf are mounts (ROS 1's first tf repeated them there): fixed
  // frames for the sensors' mounts too, unless /tf_static has them.
  std::vector<std::string> repeated_mounts;
  for (const auto& link : tree.unchanging()) {
    if (!frames_.parent(link.child)) {
      frames_.add(link.parent, link.child, link.parent_T_child);
      repeated_mounts.push_back(link.parent + " → " + link.child);
    }
  }
  if (!repeated_mounts.empty()) {
    std::string list;
    for (const auto& m : repeated_mounts) list += (list.empty() ? "" : ", ") + m;
    summary_.notes.push_back(tf_topic_ +
                             " repeats transforms that never change, taken as fixed: " + list);
  }
  return tree;
}

std::string Import::baseBelow(const std::vector<MovingFrameTree::Above>& above,
                              std::ptrdiff_t top) const {
  // As told; else the frame REP 105 names base_link when it is fixed below the moving link
  // nearest the LiDAR (odom → base_footprint → base_link → velodyne); else the frame that link
  // moves.
  std::string base = options_.base_frame;
  for (std::ptrdiff_t i = 0; base.empty() && i <= top; ++i) {
    if (!above[std::size_t(i)].moving) continue;
    base = i == 0 ? lidar_frame_ : above[std::size_t(i) - 1].frame;
    for (std::ptrdiff_t k = i - 1; k >= -1; --k) {
      const std::string& frame = k < 0 ? lidar_frame_ : above[std::size_t(k)].frame;
      const std::size_t slash = frame.rfind('/');
      if ((slash == std::string::npos ? frame : frame.substr(slash + 1)) == "base_link") {
        base = frame;
        break;
      }
    }
  }
  return base;
}

bool Import::resolveTfOdometry() {
  const MovingFrameTree tree = readTfTree();
  const auto above = tree.above(lidar_frame_, frames_);
  std::string frames = lidar_frame_;
  for (const auto& a : above) frames += (a.moving ? " ← " : " ⇠ ") + a.frame;
  const std::string chain =
      "the frames above the LiDAR's (← on " + tf_topic_ + ", ⇠ fixed): " + frames;
  const auto position = [&](const std::string& frame) {
    return std::find_if(above.begin(), above.end(),
                        [&](const MovingFrameTree::Above& a) { return a.frame == frame; }) -
           above.begin();
  };
  std::string top = options_.odometry_frame;
  if (top.empty()) {
    const auto named = std::find_if(above.begin(), above.end(),
                                    [](const auto& a) { return namedLikeOdometry(a.frame); });
    if (named != above.end()) top = named->frame;
  }
  // Asked for (--odom-topic, --odom-frame), a chain that cannot be the odometry is an error; found
  // by looking, it is left out with a note, and the recording imported without odometry.
  const bool asked = tf_asked_ || !options_.odometry_frame.empty();
  const auto give_up = [&](const std::string& why) {
    if (asked) fail(why);
    summary_.notes.push_back("no odometry taken from " + tf_topic_ + ": " + why);
    return false;
  };
  const bool moves =
      std::any_of(above.begin(), above.end(), [](const auto& a) { return a.moving; });
  if (top.empty() || position(top) == std::ptrdiff_t(above.size())) {
    if (!asked && !moves) return false;  // nothing on /tf moves the LiDAR: no odometry there
    return give_up(
        std::string(top.empty() ? "no frame named odom" : "the frame \"" + top + "\" is not") +
        " above the LiDAR's frame on " + tf_topic_ + " and /tf_static (" + chain +
        "): name the odometry's frame with --odom-frame");
  }
  // The base (baseBelow): the frame the moving link nearest the LiDAR carries.
  const std::string base = baseBelow(above, position(top));
  if (base.empty()) {
    return give_up("topic " + tf_topic_ + " moves nothing between \"" + top +
                   "\" and the LiDAR's frame (" + chain + ")");
  }
  try {
    tf_odometry_.emplace(top, base, tree.above(base, frames_));
  } catch (const std::invalid_argument& e) {
    return give_up("odometry from " + tf_topic_ + ": " + e.what() + " (" + chain + ")");
  }
  summary_.odometry.topic = tf_topic_;
  summary_.odometry.type = findTopic(tf_topic_)->recorded_type;
  summary_.odometry_chain = tf_odometry_->describe();
  odometry_frame_ = top;
  odometry_child_ = base;
  summary_.notes.push_back("the odometry is the chain " + summary_.odometry_chain + " on " +
                           tf_topic_);
  return true;
}

// The frames, from each stream's first message, and the mounts between them: a recording that
// lacks a mount fails here, before its clouds are read.
void Import::resolveFrames() {
  lidar_frame_ =
      packets_
          ? decodeFirst(summary_.lidar.topic, formats::recorded::decodeVelodyneScan).header.frame_id
          : decodeFirst(summary_.lidar.topic, formats::recorded::decodePointCloud2).header.frame_id;
  const auto poseOf = [&](const BagImportSummary::Stream& stream) {
    const bool pose = findTopic(stream.topic)->datatype == kPoseType;
    return decodeFirst(stream.topic, pose ? formats::recorded::decodePoseStamped
                                          : formats::recorded::decodeOdometry);
  };
  if (!tf_topic_.empty() && !resolveTfOdometry()) tf_topic_.clear();
  if (!summary_.odometry.topic.empty() && !tf_odometry_) {
    const formats::ros1::StampedPose first = poseOf(summary_.odometry);
    odometry_frame_ = first.header.frame_id;
    odometry_child_ = first.child_frame_id;
  }
  if (!summary_.ground_truth.topic.empty()) {
    const formats::ros1::StampedPose first = poseOf(summary_.ground_truth);
    truth_frame_ = first.header.frame_id;
    truth_child_ = first.child_frame_id;
    if (findTopic(summary_.ground_truth.topic)->datatype == kPoseType) {
      summary_.notes.push_back("the ground truth (" + summary_.ground_truth.topic +
                               ", geometry_msgs/PoseStamped) is taken as the base frame's pose");
    }
  }
  if (!summary_.imu.topic.empty()) {
    imu_frame_ = decodeFirst(summary_.imu.topic, formats::recorded::decodeImu).header.frame_id;
  }
  // The base is the odometry's child (or as told). Without odometry, the ground truth's child
  // when the fixed frames join it to the LiDAR (a rig whose truth is of its base, as our own bags
  // of a handheld carrier); else the sensor is its own base.
  const bool truth_is_of_the_rig = !summary_.ground_truth.topic.empty() && !truth_child_.empty() &&
                                   frames_.transform(truth_child_, lidar_frame_).has_value();
  base_frame_ = !options_.base_frame.empty()       ? options_.base_frame
                : !summary_.odometry.topic.empty() ? odometry_child_
                : truth_is_of_the_rig              ? truth_child_
                                                   : lidar_frame_;
  if (base_frame_.empty()) {
    fail("the odometry on " + summary_.odometry.topic +
         " names no child frame: give the base frame with --base-frame");
  }
  R_T_L_ = mount("LiDAR", "--lidar-extrinsic", lidar_frame_, options_.lidar_extrinsic);
  if (!summary_.imu.topic.empty()) {
    R_T_I_ = mount("IMU", "--imu-extrinsic", imu_frame_, options_.imu_extrinsic);
  }
  odometry_C_T_R_ = childToBase(summary_.odometry.topic, odometry_child_);
  truth_C_T_R_ = childToBase(summary_.ground_truth.topic, truth_child_);
}

void Import::readCloud(const fs::path& folder, const formats::RecordedMessage& m) {
  const formats::ros1::PointCloud2 cloud = formats::recorded::decodePointCloud2(m);
  const formats::CloudLayout layout = formats::cloudLayout(cloud);
  if (scan_stamps_.empty()) {
    layout_ = layout;
  } else if (layout.describe() != layout_.describe()) {
    throw formats::ros1::MessageError("its fields (" + layout.describe() +
                                      ") are not the first cloud's (" + layout_.describe() + ")");
  }
  if (cloud.header.frame_id != lidar_frame_) {
    throw formats::ros1::MessageError("its frame \"" + cloud.header.frame_id +
                                      "\" is not the first cloud's \"" + lidar_frame_ + "\"");
  }
  if (!scan_stamps_.empty() && !(scan_stamps_.back() < cloud.header.stamp)) {
    throw formats::ros1::MessageError("its stamp is not after the previous cloud's");
  }
  writeScan(folder, cloud.header.stamp, formats::cloudPoints(cloud, layout),
            layout.time.has_value());
}

void Import::writeScan(const fs::path& folder, formats::RosTime stamp,
                       const std::vector<sensors::ScanPoint>& points, bool timed) {
  if (timed && !points.empty()) {
    const auto [lo, hi] = std::minmax_element(
        points.begin(), points.end(),
        [](const sensors::ScanPoint& a, const sensors::ScanPoint& b) { return a.time < b.time; });
    time_min_ = clouds_with_time_ == 0 ? lo->time : std::min<double>(time_min_, lo->time);
    time_max_ = clouds_with_time_ == 0 ? hi->time : std::max<double>(time_max_, hi->time);
    ++clouds_with_time_;
    // Stamped at the end of the turn when most of its points came before the stamp.
    const auto before = std::count_if(points.begin(), points.end(),
                                      [](const sensors::ScanPoint& p) { return p.time < 0.0f; });
    if (2 * std::size_t(before) > points.size()) ++clouds_stamped_at_end_;
  }
  summary_.points += points.size();
  // Rings are numbered by elevation in a dataset: the first cloud with points decides the
  // recording's renumbering, which every cloud then takes.
  if (!ring_order_decided_ && !points.empty()) {
    ring_order_ = formats::ringsByElevation(points);
    ring_order_decided_ = true;
    if (!ring_order_.empty()) {
      std::size_t top = 0;
      for (std::size_t r = 0; r < ring_order_.size(); ++r) {
        if (ring_order_[r] > ring_order_[top]) top = r;
      }
      summary_.notes.push_back(
          "rings renumbered by elevation, 0 = lowest, as datasets number them (the recording's "
          "ring " +
          std::to_string(top) + " is the top beam, now ring " + std::to_string(ring_order_[top]) +
          ")");
    }
  }
  std::vector<sensors::ScanPoint> renumbered;
  if (!ring_order_.empty()) {
    renumbered = points;
    for (auto& p : renumbered) {
      if (p.ring < ring_order_.size()) p.ring = ring_order_[p.ring];
    }
  }
  common::writeFile(
      folder / formats::dataset::kScans / formats::dataset::scanFileName(int(scan_stamps_.size())),
      formats::dataset::pcdBytes(ring_order_.empty() ? points : renumbered,
                                 formats::dataset::kDefaultPcdData));
  scan_stamps_.push_back(stamp);
}

void Import::readPackets(const fs::path& folder, const formats::RecordedMessage& m,
                         std::uint64_t index) {
  const formats::ros1::VelodyneScan scan = formats::recorded::decodeVelodyneScan(m);
  if (scan.header.frame_id != lidar_frame_) {
    throw formats::ros1::MessageError("its frame \"" + scan.header.frame_id +
                                      "\" is not the first scan's \"" + lidar_frame_ + "\"");
  }
  formats::Vlp16DecodeOptions options;  // the ROS driver's range limits
  for (std::size_t p = 0; p < scan.packets.size(); ++p) {
    const auto& packet = scan.packets[p];
    if (packet_count_ == 0) packet_origin_ = packet.stamp.sec;
    const double stamp = double(std::int64_t(packet.stamp.sec) - std::int64_t(packet_origin_)) +
                         1e-9 * packet.stamp.nsec;
    const auto* bytes = reinterpret_cast<const std::uint8_t*>(packet.data.data());
    const std::size_t before = turn_points_.size();
    const formats::Vlp16PacketHeader header = formats::decodeVlp16Packet(
        std::span(bytes, packet.data.size()), stamp, options, bag_path_,
        "topic " + summary_.lidar.topic + ", message " + std::to_string(index) + " (" +
            formats::placeOf(m) + "), packet " + std::to_string(p),
        turn_points_);
    packet_mode_ = header.mode;
    ++packet_count_;
    // Dual-return packets give each shot's last and strongest echo: the strongest is kept, so a
    // scan has one return a shot as a single-return recording's.
    const auto weak = [](const formats::Vlp16Point& q) {
      return q.echo == formats::Vlp16Echo::kNearWeak || q.echo == formats::Vlp16Echo::kFarWeak;
    };
    const auto kept =
        std::remove_if(turn_points_.begin() + std::ptrdiff_t(before), turn_points_.end(), weak);
    weak_echoes_ += std::uint64_t(turn_points_.end() - kept);
    turn_points_.erase(kept, turn_points_.end());
  }
  // Every turn but the one under way is done; the recording's first is cut short (left out).
  std::vector<formats::Vlp16Turn> turns = formats::cutIntoTurns(turn_points_);
  if (turns.size() < 2) return;
  for (std::size_t t = 0; t + 1 < turns.size(); ++t) {
    if (!packet_turns_started_) {
      packet_turns_started_ = true;
      continue;
    }
    const auto& points = turns[t].points;
    if (points.empty()) continue;
    const double first = points.front().time;
    std::vector<sensors::ScanPoint> out;
    out.reserve(points.size());
    for (const auto& q : points) {
      out.push_back({q.x, q.y, q.z, float(q.intensity), q.ring, float(q.time - first)});
    }
    const double whole = std::floor(first);
    formats::RosTime turn_stamp{packet_origin_ + std::uint32_t(whole),
                                std::uint32_t(std::llround((first - whole) * 1e9))};
    if (turn_stamp.nsec >= 1000000000u) {
      turn_stamp.sec += 1;
      turn_stamp.nsec -= 1000000000u;
    }
    writeScan(folder, turn_stamp, out, true);
  }
  turn_points_ = std::move(turns.back().points);
}

void Import::readImu(const formats::RecordedMessage& m) {
  const formats::ros1::Imu imu = formats::recorded::decodeImu(m);
  if (imu.header.frame_id != imu_frame_) {
    throw formats::ros1::MessageError("its frame \"" + imu.header.frame_id +
                                      "\" is not the first sample's \"" + imu_frame_ + "\"");
  }
  if (imu_.empty()) {
    imu_variance_ = {imu.angular_velocity_covariance[0], imu.linear_acceleration_covariance[0]};
  }
  if (!imu_.empty() && !(imu_.back().stamp < imu.header.stamp)) {
    throw formats::ros1::MessageError("its stamp is not after the previous sample's");
  }
  sensors::ImuSample sample;
  sample.accelerometer = imu.linear_acceleration;
  sample.gyroscope = imu.angular_velocity;
  imu_.push_back({imu.header.stamp, sample});
}

void Import::readPose(const formats::RecordedMessage& m) {
  const std::string& topic = m.topic->name;
  const bool odometry = topic == summary_.odometry.topic;
  const formats::ros1::StampedPose pose = findTopic(topic)->datatype == kPoseType
                                              ? formats::recorded::decodePoseStamped(m)
                                              : formats::recorded::decodeOdometry(m);
  auto& poses = odometry ? odometry_ : truth_;
  if (pose.child_frame_id != (odometry ? odometry_child_ : truth_child_)) {
    throw formats::ros1::MessageError("its child frame \"" + pose.child_frame_id +
                                      "\" is not the first message's");
  }
  if (!poses.empty() && !(poses.back().stamp < pose.header.stamp)) {
    throw formats::ros1::MessageError("its stamp is not after the previous message's");
  }
  poses.push_back({pose.header.stamp, pose.pose});
}

void Import::readStreams(const fs::path& folder,
                         const std::function<void(std::uint64_t, std::uint64_t)>& progress) {
  std::vector<std::string> topics;
  for (auto* stream :
       {&summary_.lidar, &summary_.imu, &summary_.odometry, &summary_.ground_truth}) {
    if (!stream->topic.empty()) topics.push_back(stream->topic);
  }
  // The window, in the bag's record times.
  const formats::RosTime first = bag_->startTime();
  const double begin = double(first.sec) + 1e-9 * first.nsec + options_.start;
  const double end = options_.duration ? begin + *options_.duration : INFINITY;
  const std::uint64_t total = findTopic(summary_.lidar.topic)->messages;
  std::map<std::string, std::uint64_t> index;  // per topic: the message's place on it
  fs::create_directories(folder / formats::dataset::kScans);
  bag_->read(topics, [&](const formats::RecordedMessage& m) {
    const std::string& topic = m.topic->name;
    const std::uint64_t k = index[topic]++;
    const double time = double(m.time.sec) + 1e-9 * m.time.nsec;
    if (time < begin) return true;
    if (time > end) return false;
    try {
      if (topic == summary_.lidar.topic) {
        if (packets_) {
          readPackets(folder, m, k);
        } else {
          readCloud(folder, m);
        }
        if (progress) progress(k + 1, total);
      } else if (topic == summary_.imu.topic) {
        readImu(m);
      } else if (tf_odometry_ && topic == summary_.odometry.topic) {
        for (const auto& t : formats::recorded::decodeTfMessage(m)) {
          try {
            tf_odometry_->offer(t.header.frame_id, t.child_frame_id, t.header.stamp,
                                t.parent_T_child);
          } catch (const std::invalid_argument& e) {
            throw formats::ros1::MessageError(e.what());
          }
        }
      } else {
        readPose(m);
      }
    } catch (const formats::ros1::MessageError& e) {
      failMessage(topic, k, e.what(), &m);
    }
    return true;
  });
  if (scan_stamps_.empty()) {
    fail("topic " + summary_.lidar.topic + " has no cloud" +
         (options_.start > 0 || options_.duration ? " in the window given (--start, --duration)"
                                                  : ""));
  }
}

void Import::takeTfOdometry() {
  if (!tf_odometry_) return;
  for (const auto& pose : tf_odometry_->poses()) odometry_.push_back({pose.stamp, pose.top_T_base});
  if (odometry_.empty()) {
    fail("topic " + summary_.odometry.topic + ": no transform of the chain " +
         summary_.odometry_chain + " in the part imported");
  }
  if (tf_odometry_->repeated() > 0) {
    summary_.notes.push_back(std::to_string(tf_odometry_->repeated()) +
                             " transforms of the odometry's chain repeat their link's previous "
                             "stamp: left out");
  }
}

std::vector<sensors::ImuSample> Import::imuInDatasetTime() {
  std::vector<sensors::ImuSample> imu;
  for (const auto& s : imu_) {
    sensors::ImuSample sample = s.sample;
    sample.t = seconds(s.stamp);
    imu.push_back(sample);
  }
  if (imu.empty()) return imu;
  // The IMU's units: m/s² unless the specific force's median norm over the first second says g.
  std::vector<double> norms;
  for (const auto& s : imu) {
    if (s.t > imu.front().t + 1.0) break;
    norms.push_back(s.accelerometer.norm());
  }
  std::nth_element(norms.begin(), norms.begin() + norms.size() / 2, norms.end());
  const double median = norms[norms.size() / 2];
  if (std::abs(median - 1.0) < kGravityInG) {
    for (auto& s : imu) s.accelerometer *= kStandardGravity;
    imu_variance_[1] *= kStandardGravity * kStandardGravity;
    char line[160];
    std::snprintf(line, sizeof line,
                  "the IMU's specific force is in g (median norm %.3f over its first second): "
                  "converted to m/s²",
                  median);
    summary_.notes.push_back(line);
  }
  return imu;
}

std::vector<double> Import::scansWithinOdometry(const fs::path& folder,
                                                const common::Trajectory& odometry) {
  std::vector<double> stamps;
  for (const auto& s : scan_stamps_) stamps.push_back(seconds(s));
  std::size_t first = 0, last = stamps.size();
  if (!odometry.empty()) {
    while (first < last && stamps[first] < odometry.front().t) ++first;
    while (last > first && stamps[last - 1] > odometry.back().t) --last;
    if (first == last) {
      fail("no cloud on " + summary_.lidar.topic + " lies within the odometry's time span (" +
           summary_.odometry.topic + ")");
    }
    if (first > 0 || last < stamps.size()) {
      summary_.notes.push_back(std::to_string(first + stamps.size() - last) +
                               " clouds outside the odometry's time span left out");
    }
  }
  const fs::path scans = folder / formats::dataset::kScans;
  for (std::size_t i = 0; i < stamps.size(); ++i) {
    const fs::path file = scans / formats::dataset::scanFileName(int(i));
    if (i < first || i >= last) {
      fs::remove(file);
    } else if (first > 0) {
      fs::rename(file, scans / formats::dataset::scanFileName(int(i - first)));
    }
  }
  return std::vector<double>(stamps.begin() + std::ptrdiff_t(first),
                             stamps.begin() + std::ptrdiff_t(last));
}

void Import::writeScanTimes(const fs::path& folder, const std::vector<double>& stamps,
                            const common::Trajectory& truth) {
  // scans.tum when the ground truth covers every scan, else the stamps alone.
  common::Trajectory scan_poses;
  for (double t : stamps) {
    const auto B_T_R = common::interpolatePose(truth, t);
    if (!B_T_R) break;
    scan_poses.push_back({t, *B_T_R * R_T_L_});
  }
  if (!truth.empty() && scan_poses.size() == stamps.size()) {
    common::writeFile(folder / formats::dataset::kScanPoses,
                      formats::dataset::trajectoryText(scan_poses));
    return;
  }
  if (!truth.empty()) {
    summary_.notes.push_back(
        "the ground truth does not cover every scan: scans.txt holds "
        "their stamps, without poses");
  }
  common::writeFile(folder / formats::dataset::kScanStamps, formats::dataset::stampsText(stamps));
}

void Import::writeFiles(const fs::path& folder) {
  takeTfOdometry();
  // Dataset time 0: the whole second at or before the first imported stamp.
  origin_ = scan_stamps_.front().sec;
  for (const auto& s : imu_) origin_ = std::min(origin_, s.stamp.sec);
  for (const auto* poses : {&odometry_, &truth_}) {
    if (!poses->empty()) origin_ = std::min(origin_, poses->front().stamp.sec);
  }
  common::Trajectory odometry, truth;
  for (const auto& p : odometry_) odometry.push_back({seconds(p.stamp), p.pose * odometry_C_T_R_});
  for (const auto& p : truth_) truth.push_back({seconds(p.stamp), p.pose * truth_C_T_R_});
  const std::vector<sensors::ImuSample> imu = imuInDatasetTime();
  // Scans outside the odometry's span would have no motion prior: left out.
  const std::vector<double> stamps = scansWithinOdometry(folder, odometry);
  summary_.lidar.messages = stamps.size();
  summary_.imu.messages = imu.size();
  summary_.odometry.messages = odometry.size();
  summary_.ground_truth.messages = truth.size();
  // The turn about its stamp.
  summary_.scan_period = formats::dataset::meanPeriod(stamps).value_or(0.1);
  summary_.point_time = clouds_with_time_ > 0 && time_max_ > time_min_
                            ? std::array<double, 2>{time_min_, time_max_}
                            : std::array<double, 2>{0.0, summary_.scan_period};
  summary_.stamp = 2 * clouds_stamped_at_end_ > clouds_with_time_ ? "last_packet" : "first_firing";
  summary_.cloud_layout =
      packets_ ? "x y z intensity ring time (VLP-16 packets decoded)" : layout_.describe();
  if (packets_) {
    const char* mode = packet_mode_ == formats::Vlp16ReturnMode::kDual   ? "dual"
                       : packet_mode_ == formats::Vlp16ReturnMode::kLast ? "last"
                                                                         : "strongest";
    summary_.notes.push_back(common::counted(packet_count_, "VLP-16 packet") + " decoded (" + mode +
                             " return) into " + common::counted(scan_stamps_.size(), "turn") +
                             " cut at azimuth 0; the first and the last turn, cut short, left out" +
                             (weak_echoes_ > 0 ? "; the weaker echo of " +
                                                     common::counted(weak_echoes_, "shot") +
                                                     " left out (one return a shot)"
                                               : ""));
  }
  summary_.seconds = stamps.back() + summary_.point_time[1];

  writeScanTimes(folder, stamps, truth);
  if (!odometry.empty())
    common::writeFile(folder / formats::dataset::kOdometry,
                      formats::dataset::trajectoryText(odometry));
  if (!truth.empty())
    common::writeFile(folder / formats::dataset::kGroundTruth,
                      formats::dataset::trajectoryText(truth));
  if (!imu.empty())
    common::writeFile(folder / formats::dataset::kImu, formats::dataset::imuText(imu));
  common::writeFile(folder / formats::dataset::kMetadata,
                    datasetMetadata(stamps, imu, odometry).dump(2) + "\n");
}

nlohmann::ordered_json Import::datasetMetadata(const std::vector<double>& stamps,
                                               const std::vector<sensors::ImuSample>& imu,
                                               const common::Trajectory& odometry) {
  nlohmann::ordered_json m;
  if (isg_metadata_) {
    // An isg dataset exported to a bag: its own metadata back, counts and span as imported.
    summary_.from_isg = true;
    m = formats::dataset::inMetadataOrder(nlohmann::ordered_json::parse(isg_metadata_->dump()));
    if (options_.start > 0 || options_.duration) {
      m["duration_s"] = summary_.seconds;
      m["lidar"]["scans"] = stamps.size();
      if (m.contains("imu") && m["imu"].is_object()) m["imu"]["samples"] = imu.size();
    }
    m["lidar"]["pcd_data"] = formats::dataset::pcdDataName(formats::dataset::kDefaultPcdData);
  } else {
    m = metadata(stamps, imu, odometry);
  }
  m["imported_from"] = {{"file", fs::path(bag_path_).filename().string()},
                        {"start_s", options_.start},
                        {"time_origin_s", origin_},
                        {"topics",
                         {{"lidar", summary_.lidar.topic},
                          {"imu", summary_.imu.topic},
                          {"odometry", summary_.odometry.topic},
                          {"ground_truth", summary_.ground_truth.topic}}},
                        {"notes", summary_.notes}};
  if (options_.duration) m["imported_from"]["duration_s"] = *options_.duration;
  return m;
}

nlohmann::ordered_json Import::metadata(const std::vector<double>& stamps,
                                        const std::vector<sensors::ImuSample>& imu,
                                        const common::Trajectory& odometry) const {
  formats::dataset::Metadata m;
  m.generator = std::string("isg import ") + common::kProjectVersion;
  m.duration_s = summary_.seconds;
  m.frames = {{"B", truth_frame_.empty() ? "plan frame (no ground truth recorded)" : truth_frame_},
              {"M", odometry_frame_.empty() ? "odometry frame (none recorded)" : odometry_frame_},
              {"R", base_frame_},
              {"L", lidar_frame_},
              {"I", imu_frame_.empty() ? "(no IMU recorded)" : imu_frame_}};
  m.lidar_mount = sensors::mountXyzRpy(R_T_L_);
  m.R_T_L = R_T_L_;
  m.lidar = {"recorded",
             1.0 / summary_.scan_period,
             stamps.size(),
             summary_.stamp,
             summary_.scan_period,
             summary_.point_time,
             formats::dataset::kDefaultPcdData};
  nlohmann::ordered_json description = {{"lidar", {{"fields", summary_.cloud_layout}}}};
  if (!imu.empty()) {
    m.imu_mount = {sensors::mountXyzRpy(R_T_I_), R_T_I_};
    std::vector<double> times;
    for (const auto& s : imu) times.push_back(s.t);
    const double rate = imu.size() >= 2 ? 1.0 / *formats::dataset::meanPeriod(times) : 0.0;
    m.imu = formats::dataset::Metadata::Imu{rate, imu.size(), std::nullopt, std::nullopt};
    // The message's per-sample variances are density² × rate; given only when the driver
    // filled them.
    if (imu_variance_[0] > 0 && imu_variance_[1] > 0 && rate > 0) {
      m.imu->gyroscope_noise_density = std::sqrt(imu_variance_[0] / rate);
      m.imu->accelerometer_noise_density = std::sqrt(imu_variance_[1] / rate);
    }
  }
  if (!odometry.empty()) {
    std::vector<double> times;
    for (const auto& p : odometry) times.push_back(p.t);
    m.odometry = {times.size() >= 2 ? 1.0 / *formats::dataset::meanPeriod(times) : 0.0};
    description["odometry"] = {{"topic", summary_.odometry.topic}};
    if (tf_odometry_) description["odometry"]["chain"] = summary_.odometry_chain;
  }
  return formats::dataset::metadataJson(m, description);
}

BagImportSummary Import::run(const fs::path& folder,
                             const std::function<void(std::uint64_t, std::uint64_t)>& progress) {
  collectTopics();
  chooseTopics();
  readStatic();
  resolveFrames();
  readStreams(folder, progress);
  writeFiles(folder);
  return summary_;
}

}  // namespace

BagImportSummary importRosbag(const std::string& bag_path, const std::string& dataset_dir,
                              const BagImportOptions& options,
                              const std::function<void(std::uint64_t, std::uint64_t)>& progress) {
  Import import(bag_path, options);
  BagImportSummary summary;
  common::writeFolderAtomically(
      dataset_dir, common::OutputKind::kDataset, options.overwrite,
      [&](const fs::path& folder) { summary = import.run(folder, progress); });
  return summary;
}

}  // namespace isg::recordings
