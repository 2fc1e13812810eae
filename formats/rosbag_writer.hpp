#pragma once

#include <cstdint>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "common/atomic_folder.hpp"
#include "formats/ros_time.hpp"

namespace isg::formats {

// What a bag records of a message type: its name, MD5 and full definition (as gencpp emits them).
struct RosMessageType {
  std::string datatype;    // "sensor_msgs/Imu"
  std::string md5sum;      // 32 hex digits
  std::string definition;  // the .msg text with every nested type's appended
};

// Writes a ROS 1 bag, format 2.0, uncompressed (docs/formats.md, "ROS bags"): the version line, a
// 4096-byte bag header record, chunks of connection and message records each followed by its
// index records, then every connection record and one chunk-info record per chunk, the header
// rewritten at the end to point at them. The file appears at `path` only when close() returns
// (AtomicFile); an error or a destruction without close() leaves nothing.
class RosbagWriter {
 public:
  RosbagWriter(const std::string& path, bool overwrite);

  // A topic of one message type; latched topics (/tf_static) say so to players.
  int connect(const std::string& topic, const RosMessageType& type, bool latching = false);
  // One serialised message on `connection`, recorded at `time`. Messages of a connection must come
  // in time order (the index is read that way).
  void write(int connection, RosTime time, const std::string& serialised);
  void close();

  std::uint64_t bytesWritten() const { return position_; }
  // Messages written per connection.
  const std::vector<std::uint64_t>& counts() const { return counts_; }

 private:
  struct Connection {
    std::string topic;
    RosMessageType type;
    bool latching = false;
  };
  struct IndexEntry {
    RosTime time;
    std::uint32_t offset;  // of the message record in the chunk's data
  };
  struct ChunkInfo {
    std::uint64_t position = 0;
    RosTime start, end;
    std::map<int, std::uint32_t> counts;  // per connection
  };
  std::string connectionRecord(int id) const;
  void flushChunk();
  void put(const std::string& bytes);

  common::AtomicFile file_;
  std::ofstream out_;
  std::uint64_t position_ = 0;
  std::vector<Connection> connections_;
  std::vector<std::uint64_t> counts_;
  std::vector<bool> connection_written_;  // its record is in some chunk already
  std::string chunk_;                     // the open chunk's records
  std::map<int, std::vector<IndexEntry>> chunk_index_;
  ChunkInfo chunk_info_;
  std::vector<ChunkInfo> chunks_;
  bool closed_ = false;
};

}  // namespace isg::formats
