#pragma once

#include <cstdint>
#include <functional>
#include <istream>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "formats/chunk_cache.hpp"

namespace isg::formats {

// A channel of an MCAP file with its schema (name, encoding and text; all "" when it has none).
struct McapChannel {
  std::uint16_t id = 0;
  std::string topic;
  std::string message_encoding;  // "cdr" for ROS 2, "ros1", "json", …
  std::map<std::string, std::string> metadata;
  std::string schema_name;      // "sensor_msgs/msg/PointCloud2"
  std::string schema_encoding;  // "ros2msg", "ros2idl", "ros1msg", "jsonschema", …
  std::string schema_data;
  std::uint64_t messages = 0;  // in the file
};

// One message as read: valid until the visitor returns.
struct McapMessageView {
  const McapChannel* channel = nullptr;
  std::uint32_t sequence = 0;
  std::uint64_t log_time_ns = 0;
  std::uint64_t publish_time_ns = 0;
  std::string_view data;
  std::uint64_t index = 0;  // its place among the messages read, from 0
  // Where its record is, for errors: at byte `record_offset` of the file, or, when `chunk_offset`
  // is not 0, at byte `record_offset` of the records of the chunk at byte `chunk_offset`.
  std::uint64_t record_offset = 0, chunk_offset = 0;
};

// Reads an MCAP file (https://mcap.dev/spec), whoever wrote it: the magic at both ends, the
// Header, then the data section record by record — Schemas, Channels and Messages at the top level
// or inside Chunks (uncompressed, zstd or lz4; each chunk's CRC-32 checked when it has one) — up
// to Data End; the summary section is not needed and not trusted. Unknown records are skipped, as
// the specification asks. Messages are delivered in log-time order, ties in the file's order, as
// the MCAP libraries' readers give them. Errors throw common::InputError naming the file, the
// record's byte offset and what is wrong: not an MCAP file, cut short (no closing magic: `mcap
// recover` mends it), a record out of bounds, a message on an unknown channel, a channel
// redefined differently, a chunk that does not decompress to its size or fails its CRC.
class McapReader {
 public:
  explicit McapReader(const std::string& path);
  // The file's bytes in memory; `name` names it in messages (tests and the fuzz harness).
  McapReader(std::string bytes, const std::string& name);
  ~McapReader();
  McapReader(const McapReader&) = delete;
  McapReader& operator=(const McapReader&) = delete;

  const std::string& name() const { return name_; }
  const std::string& profile() const { return profile_; }  // the Header's ("ros2", "ros1", "")
  const std::string& library() const { return library_; }
  const std::vector<McapChannel>& channels() const { return channels_; }
  std::uint64_t messageCount() const { return entries_.size(); }
  // The first and last messages' log times (0 when there are none).
  std::uint64_t firstLogTime() const { return entries_.empty() ? 0 : entries_.front().log_time; }
  std::uint64_t lastLogTime() const { return entries_.empty() ? 0 : entries_.back().log_time; }
  // The chunks' compressions, each once, in the order first met ("none", "zstd", "lz4").
  const std::vector<std::string>& compressions() const { return compressions_; }

  // Every message on `topics` (every topic when empty) in log-time order; `visit` returns false
  // to stop.
  void read(const std::vector<std::string>& topics,
            const std::function<bool(const McapMessageView&)>& visit);

 private:
  struct Chunk {
    std::uint64_t position = 0;     // of its record in the file
    std::uint64_t data_offset = 0;  // of its (compressed) records
    std::uint64_t data_size = 0;
    std::uint64_t size = 0;  // uncompressed
    std::uint32_t crc = 0;   // of the uncompressed records; 0: none
    std::string compression;
  };
  struct Entry {
    std::uint64_t log_time = 0;
    std::uint64_t position = 0;  // of the message record: in the file, or in the chunk's records
    std::uint32_t chunk = kNoChunk;
    std::uint32_t channel = 0;  // the channel's id while the file is read, then its index
  };
  static constexpr std::uint32_t kNoChunk = 0xffffffffu;
  struct SchemaRecord {
    std::string name, encoding, data;
  };

  void open();
  // A Schema, Channel or Message record's content (`content` at `offset`: in the file or, for a
  // record inside chunk `chunk`, the chunk's uncompressed records).
  void readRecord(std::uint8_t opcode, std::string_view content, std::uint64_t offset,
                  std::uint32_t chunk);
  void readChunk(std::string_view content, std::uint64_t position);
  const std::string& loadChunk(std::uint32_t chunk);
  [[noreturn]] void fail(std::uint64_t offset, const std::string& what) const;

  std::string name_;
  std::unique_ptr<std::istream> in_;
  std::uint64_t size_ = 0;
  std::string profile_, library_;
  std::map<std::uint16_t, SchemaRecord> schemas_;
  std::map<std::uint16_t, std::uint32_t> channel_index_;  // channel id → index in channels_
  std::vector<McapChannel> channels_;
  std::vector<Chunk> chunks_;
  std::vector<Entry> entries_;  // sorted by log time, then file order (after open)
  std::vector<std::string> compressions_;
  ChunkCache cache_{4};  // the last chunks read, uncompressed
};

}  // namespace isg::formats
