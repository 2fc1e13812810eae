#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "formats/rosbag_writer.hpp"

namespace isg::formats {

// How a recording's messages are serialised, which decides how they are decoded.
enum class MessageEncoding {
  kRos1,   // ROS 1's serialisation (a .bag, or an MCAP channel of "ros1")
  kCdr,    // ROS 2's CDR with its encapsulation header (rosbag2, an MCAP channel of "cdr")
  kOther,  // anything else (an MCAP channel of "json", "protobuf", …): not decoded
};

// A topic of a recording as one publisher recorded it: a ROS 1 bag's connection, an MCAP channel,
// a row of rosbag2's topics table. One topic may appear more than once (several publishers).
struct RecordedTopic {
  std::string name;
  std::string type;           // in ROS 1's spelling whichever ROS recorded it: "sensor_msgs/Imu"
  std::string recorded_type;  // as the recording names it: "sensor_msgs/msg/Imu" in ROS 2's
  std::string md5sum;         // ROS 1's definition MD5 ("*": any); "" when the recording has none
  MessageEncoding encoding = MessageEncoding::kRos1;
  std::string encoding_name;  // as the recording names it: "ros1", "cdr", "json", …
  std::uint64_t messages = 0;
};

// One message as read: valid until the visitor returns.
struct RecordedMessage {
  const RecordedTopic* topic = nullptr;
  RosTime time;           // when it was recorded (the recorder's receive time)
  std::string_view data;  // serialised in topic->encoding
  // Where it is, for errors (placeOf): the storage file when the recording has several; an SQLite
  // row; or the byte of its record, in the file or in the chunk at byte `chunk_byte` (not 0).
  const std::string* file = nullptr;
  std::int64_t row = -1;
  std::uint64_t byte = 0, chunk_byte = 0;
};

// "row 12 of walk_0.db3", "the record at byte 4096", "byte 96 of the chunk at byte 4096"; "" when
// the recording gives no place (a ROS 1 bag, whose messages the import names by their index).
std::string placeOf(const RecordedMessage& message);

// A robot's recording, whichever container holds it: a ROS 1 bag, a rosbag2 bag (its folder with
// metadata.yaml, split files in its order, in the sqlite3 or the MCAP storage; or one .db3), or an
// MCAP file (ROS 2's CDR with ros2msg or ros2idl schemas, or ROS 1's). Each is read by its own
// checked reader (RosbagReader, Ros2Bag, McapReader); errors are common::InputErrors naming the
// file and the place.
class Recording {
 public:
  virtual ~Recording() = default;
  Recording(const Recording&) = delete;
  Recording& operator=(const Recording&) = delete;

  const std::string& path() const { return path_; }
  // "ROS 1 bag", "rosbag2 (sqlite3)", "rosbag2 (mcap)", "MCAP".
  const std::string& kind() const { return kind_; }
  const std::vector<RecordedTopic>& topics() const { return topics_; }
  // The first message's record time (0 when there is none).
  RosTime startTime() const { return start_; }
  // Every message on `topics` (by name; every topic when empty) in record-time order; `visit`
  // returns false to stop.
  virtual void read(const std::vector<std::string>& topics,
                    const std::function<bool(const RecordedMessage&)>& visit) = 0;

 protected:
  Recording(std::string path, std::string kind) : path_(std::move(path)), kind_(std::move(kind)) {}
  std::vector<RecordedTopic> topics_;
  RosTime start_;

 private:
  std::string path_, kind_;
};

// Opens the recording at `path`: a .bag, a .db3, a .mcap, or a rosbag2 folder. Anything else is a
// common::InputError saying what it is not.
std::unique_ptr<Recording> openRecording(const std::string& path);

// True when `path` names a recording by its form: a .bag, .db3 or .mcap file, or a folder with
// a rosbag2 metadata.yaml or .db3 files.
bool isRecordingPath(const std::string& path);

// ROS 1's spelling of a ROS 2 type name: "sensor_msgs/msg/Imu" → "sensor_msgs/Imu" (other names
// as they are).
std::string ros1TypeName(const std::string& type);

// The record time of `ns` nanoseconds since the epoch; an std::invalid_argument when it is before
// 1970 or past a RosTime's 2106.
RosTime rosTimeOfNanoseconds(std::int64_t ns);

}  // namespace isg::formats
