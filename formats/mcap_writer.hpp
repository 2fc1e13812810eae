#pragma once

#include <cstdint>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "common/atomic_folder.hpp"

namespace isg::formats {

// How an MCAP file's chunks are compressed: not at all, zstd (Debian's libzstd) or the LZ4 frame
// format (Debian's liblz4) — the two the MCAP specification names.
enum class McapCompression { kNone, kZstd, kLz4 };
// "none", "zstd", "lz4": as the command line spells them.
const char* compressionName(McapCompression compression);

struct McapWriterOptions {
  McapCompression compression = McapCompression::kZstd;
  // Uncompressed bytes of messages a chunk holds before it is closed (as the MCAP libraries'
  // default, 4 MiB: a reader seeks by chunk and holds one in memory).
  std::size_t chunk_size = 4 << 20;
  std::string profile = "ros2";  // the Header's profile: which conventions the channels follow
  bool overwrite = false;
};

// Writes an MCAP file (docs/formats.md, "MCAP"): magic, Header, then chunks of Schema, Channel
// and Message records each followed by its Message Index records, Data End with the CRC-32 of all
// that, and a Summary section — every Schema and Channel again, Statistics, one Chunk Index per
// chunk — with one Summary Offset per group of it, the Footer (with the summary's CRC-32) and the
// magic again. Every chunk carries the CRC-32 of its uncompressed records. The file appears at
// `path` only when close() returns (AtomicFile); an error or a destruction without close() leaves
// nothing.
class McapWriter {
 public:
  McapWriter(const std::string& path, const McapWriterOptions& options);

  // A schema: its name ("sensor_msgs/msg/Imu"), encoding ("ros2msg", "jsonschema") and text.
  std::uint16_t addSchema(const std::string& name, const std::string& encoding,
                          const std::string& data);
  // A channel of messages of `schema` on `topic`, encoded as `message_encoding` ("cdr", "json").
  std::uint16_t addChannel(std::uint16_t schema, const std::string& topic,
                           const std::string& message_encoding,
                           const std::map<std::string, std::string>& metadata = {});
  // One message; its sequence number is its count on the channel. Log time = publish time, ns.
  void write(std::uint16_t channel, std::uint64_t log_time_ns, const std::string& data);
  void close();

  std::uint64_t bytesWritten() const { return position_; }
  // Messages written per channel (index = channel id).
  const std::vector<std::uint64_t>& counts() const { return counts_; }

 private:
  struct Schema {
    std::string name, encoding, data;
  };
  struct Channel {
    std::uint16_t schema = 0;
    std::string topic, message_encoding;
    std::map<std::string, std::string> metadata;
  };
  struct ChunkIndex {
    std::uint64_t start = 0, end = 0;  // message log times
    std::uint64_t offset = 0, length = 0;
    std::map<std::uint16_t, std::uint64_t> message_index_offsets;
    std::uint64_t message_index_length = 0;
    std::uint64_t compressed_size = 0, uncompressed_size = 0;
  };
  void flushChunk();
  // The compression a Chunk and its Chunk Index name: "" for none.
  std::string chunkCompression() const;
  void put(const std::string& bytes);

  McapWriterOptions options_;
  common::AtomicFile file_;
  std::ofstream out_;
  std::uint64_t position_ = 0;
  std::uint32_t data_crc_;  // running CRC-32 of the data section so far
  bool data_ended_ = false;
  std::vector<Schema> schemas_;
  std::vector<Channel> channels_;
  std::vector<std::uint64_t> counts_;
  // The open chunk: its records, which schemas and channels it declared, its messages' index.
  std::string chunk_;
  std::vector<bool> schema_in_chunk_, channel_in_chunk_;
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_messages_;
  std::uint64_t chunk_start_ = 0, chunk_end_ = 0;
  std::vector<ChunkIndex> chunks_;
  std::uint64_t message_start_ = 0, message_end_ = 0, messages_ = 0;
  bool closed_ = false;
};

// CRC-32 (as MCAP computes it: zlib's) of `bytes`, continuing from `crc` (0 to start).
std::uint32_t crc32(const std::string& bytes, std::uint32_t crc = 0);

}  // namespace isg::formats
