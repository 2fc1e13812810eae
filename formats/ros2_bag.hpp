#pragma once

#include <cstdint>
#include <string>
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

// A ROS 2 bag in the sqlite3 storage (rosbag2's default before Iron): the bag's folder (its
// metadata.yaml names the .db3 files; every *.db3 in it is read, in name order) or one .db3 file.
// Read with Debian's libsqlite3, read-only. Problems — no such file, not an SQLite database, no
// such topic — are bim::InputErrors naming the file.
class Ros2Bag {
 public:
  explicit Ros2Bag(const std::string& path);

  const std::vector<Ros2Topic>& topics() const { return topics_; }
  // The topic's messages in stamp order; an InputError listing the bag's topics when it has none
  // by that name.
  std::vector<Ros2Message> messages(const std::string& topic) const;

 private:
  std::string path_;
  std::vector<std::string> files_;
  std::vector<Ros2Topic> topics_;
};

}  // namespace isg::formats
