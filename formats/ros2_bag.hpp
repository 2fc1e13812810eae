#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace isg::formats {

// A topic of a ROS 2 bag.
struct Ros2Topic {
  std::string name;
  std::string type;                  // e.g. "velodyne_msgs/msg/VelodyneScan"
  std::string serialization_format;  // "cdr" for every bag ROS 2 writes by default
  std::size_t messages = 0;
};

// One serialised message.
struct Ros2Message {
  std::int64_t stamp_ns = 0;  // the recorder's receive time, ns since the epoch
  std::string data;           // CDR bytes, with their 4-byte encapsulation header
};

// One message as read by Ros2Bag::read: valid until the visitor returns.
struct Ros2MessageView {
  const Ros2Topic* topic = nullptr;
  std::int64_t stamp_ns = 0;          // the recorder's receive time, ns since the epoch
  std::string_view data;              // CDR bytes, with their 4-byte encapsulation header
  std::uint64_t index = 0;            // its place among the messages read, from 0
  const std::string* file = nullptr;  // the storage file it is in
  std::int64_t row = 0;               // its row in that file's messages table (id)
};

// What a rosbag2 folder's metadata.yaml (rosbag2_bagfile_information) says of its storage: the
// storage identifier ("sqlite3" when it names none, as before Humble; or "mcap") and the files it
// names, in its order (a split bag), each checked to be in the folder. A compressed bag, an
// unknown storage and a file that is not rosbag2's metadata are common::InputErrors naming it.
struct Rosbag2Storage {
  std::string storage;
  std::vector<std::string> files;
};
Rosbag2Storage readRosbag2Metadata(const std::string& metadata_file);

// A ROS 2 bag in the sqlite3 storage (rosbag2's default before Iron): the bag's folder or one .db3
// file. A folder's metadata.yaml (rosbag2_bagfile_information: storage_identifier,
// relative_file_paths, compression_mode) names its files, read in its order (a split bag); a
// folder without one is read as its *.db3 files in name order. The MCAP storage and compressed
// bags are refused, saying so.
// Read with Debian's libsqlite3, read-only. Problems — no such file, not an SQLite database, no
// such topic — are bim::InputErrors naming the file.
class Ros2Bag {
 public:
  explicit Ros2Bag(const std::string& path);

  const std::vector<Ros2Topic>& topics() const { return topics_; }
  const std::vector<std::string>& files() const { return files_; }
  // The first message's stamp, ns since the epoch (0 when the bag has none).
  std::int64_t startNs() const { return start_ns_; }
  // The topic's messages in stamp order; an InputError listing the bag's topics when it has none
  // by that name.
  std::vector<Ros2Message> messages(const std::string& topic) const;
  // Every message on `topics` (every topic when empty) in stamp order across the bag's files, ties
  // in the files' order and then by row, one message in memory at a time; `visit` returns false to
  // stop. An InputError, as messages() gives, for a topic the bag does not have.
  void read(const std::vector<std::string>& topics,
            const std::function<bool(const Ros2MessageView&)>& visit) const;

 private:
  // An InputError listing the bag's topics unless it has `topic`.
  void expectTopic(const std::string& topic) const;

  std::string path_;
  std::vector<std::string> files_;
  std::vector<Ros2Topic> topics_;
  std::int64_t start_ns_ = 0;
};

}  // namespace isg::formats
