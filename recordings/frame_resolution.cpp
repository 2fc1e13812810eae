#include "recordings/bag_import_parts.hpp"

namespace isg::recordings::bag_import {

// A transform that closes a cycle of frames: tf's frames form a tree, and tf itself refuses the
// lookup through one, so the import refuses it too rather than drop a link unsaid.
std::string cycleMessage(const std::string& parent, const std::string& child,
                         const std::string& cycle) {
  if (parent == child) return "the frame \"" + child + "\" hangs from itself";
  return "the transform \"" + parent + "\" → \"" + child + "\" closes a cycle of frames (" + cycle +
         "); tf's frames form a tree";
}

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

}  // namespace isg::recordings::bag_import
