#pragma once

#include <cstdint>
#include <functional>
#include <istream>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "formats/chunk_cache.hpp"

#include "formats/rosbag_writer.hpp"

namespace isg::formats {

// A topic of a ROS 1 bag: its connection record.
struct BagConnection {
  std::uint32_t id = 0;  // the bag's connection number
  std::string topic;
  RosMessageType type;
  std::string callerid;  // "" when the record has none
  bool latching = false;
  std::uint64_t messages = 0;  // in the bag, from its chunk infos
};

// One message as read: valid until the visitor returns.
struct BagMessageView {
  const BagConnection* connection = nullptr;
  RosTime time;
  std::string_view data;    // the serialised message
  std::uint64_t index = 0;  // its place among the messages read, from 0
};

// Reads a ROS 1 bag, format 2.0 (docs/formats.md, "ROS bags"), as rosbag's own reader does: the
// bag header, then the index at its end (connection records and one chunk info a chunk), then each
// chunk's index records, which give every message's time and place. Chunks may be stored plain or
// compressed with bz2 or lz4 (the LZ4 frame format that roslz4 writes). Messages are delivered in
// time order whatever the chunks' order, ties by connection number and then in the bag's order,
// as rosbag's read_messages gives them. Errors throw common::InputError naming the file, the
// record's byte offset and what is wrong: not a bag, another version, not indexed (a recording cut
// short: `rosbag reindex` mends it), truncated, a record or field out of bounds, an unknown
// compression.
class RosbagReader {
 public:
  explicit RosbagReader(const std::string& path);
  // The bag's bytes in memory; `name` names it in messages (tests and the fuzz harness).
  RosbagReader(std::string bytes, const std::string& name);
  ~RosbagReader();
  RosbagReader(const RosbagReader&) = delete;
  RosbagReader& operator=(const RosbagReader&) = delete;

  const std::string& name() const { return name_; }
  const std::vector<BagConnection>& connections() const { return connections_; }
  std::uint64_t messageCount() const { return entries_.size(); }
  // The first and last message's time (zero for a bag without messages).
  RosTime startTime() const;
  RosTime endTime() const;
  // The chunks' compressions, each once, in the order first met ("none", "bz2", "lz4").
  const std::vector<std::string>& compressions() const { return compressions_; }

  // Every message on `topics` (every topic when empty) in time order; `visit` returns false to
  // stop. Throws on a damaged chunk or message record.
  void read(const std::vector<std::string>& topics,
            const std::function<bool(const BagMessageView&)>& visit);

 private:
  struct Chunk {
    std::uint64_t position = 0;     // of its chunk record in the file
    std::uint64_t data_offset = 0;  // of its (compressed) data
    std::uint32_t data_size = 0;
    std::uint32_t size = 0;  // uncompressed
    std::string compression;
  };
  struct Entry {
    RosTime time;
    std::uint32_t chunk = 0;
    std::uint32_t offset = 0;  // of the message record in the uncompressed chunk
    // Index into connections_ (its connection number as read, until readIndex maps it).
    std::uint32_t connection = 0;
  };
  void open();
  void readIndex(std::uint64_t index_position, std::uint32_t connection_count,
                 std::uint32_t chunk_count);
  // A chunk's record: its compression, sizes and where its data is (its info gave its position).
  void readChunkRecord(std::uint32_t chunk, std::uint64_t index_position);
  void readChunkIndex(std::uint32_t chunk, std::uint32_t index_records);
  const std::string& loadChunk(std::uint32_t chunk);
  [[noreturn]] void fail(std::uint64_t offset, const std::string& what) const;

  std::string name_;
  std::unique_ptr<std::istream> in_;
  std::uint64_t size_ = 0;
  std::vector<BagConnection> connections_;
  std::vector<Chunk> chunks_;
  std::vector<Entry> entries_;  // sorted by time, then file order
  std::vector<std::string> compressions_;
  // The last chunks read, uncompressed: topics recorded with different delays interleave
  // neighbouring chunks in time, and each would otherwise be decompressed again and again.
  ChunkCache cache_{8};
};

}  // namespace isg::formats
