#include "recordings/bag_import_parts.hpp"

namespace isg::recordings::bag_import {

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

}  // namespace isg::recordings::bag_import
