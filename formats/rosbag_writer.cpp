#include "formats/rosbag_writer.hpp"

#include <bit>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "common/input_error.hpp"
#include "formats/rosbag_format.hpp"

namespace isg::formats {

namespace {

using rosbag::kVersionLine;
constexpr std::size_t kBagHeaderRecordSize = 4096;  // the header record is padded to this
// A chunk is closed once it holds this many bytes (rosbag's own default threshold).
constexpr std::size_t kChunkThreshold = 768 * 1024;

using rosbag::kBagHeader;
using rosbag::kChunk;
using rosbag::kChunkInfo;
using rosbag::kConnection;
using rosbag::kIndexData;
using rosbag::kMessageData;

// Little-endian integers, as the format has them (and as this machine stores them).
template <typename T>
std::string littleEndianBytes(T value) {
  static_assert(std::endian::native == std::endian::little);
  std::string out(sizeof(T), '\0');
  std::memcpy(out.data(), &value, sizeof(T));
  return out;
}

std::string timeBytes(RosTime t) { return littleEndianBytes(t.sec) + littleEndianBytes(t.nsec); }

// A header field: its length, then "name=value".
std::string field(const std::string& name, const std::string& value) {
  return littleEndianBytes(std::uint32_t(name.size() + 1 + value.size())) + name + "=" + value;
}

std::string bagRecord(const std::string& header, const std::string& data) {
  return littleEndianBytes(std::uint32_t(header.size())) + header +
         littleEndianBytes(std::uint32_t(data.size())) + data;
}

std::string bagHeaderRecord(std::uint64_t index_position, std::uint32_t connections,
                            std::uint32_t chunks) {
  const std::string header = field("op", littleEndianBytes(std::uint8_t(kBagHeader))) +
                             field("index_pos", littleEndianBytes(index_position)) +
                             field("conn_count", littleEndianBytes(connections)) +
                             field("chunk_count", littleEndianBytes(chunks));
  // Padded with spaces so that the record can be rewritten in place when the bag is closed; the
  // padding starts with our mark, which readers skip and --force looks for
  // (sensors/output_path.hpp).
  std::string padding(kBagHeaderRecordSize - header.size() - 8, ' ');
  padding.replace(0, std::strlen(common::kWrittenByIsg), common::kWrittenByIsg);
  return bagRecord(header, padding);
}

}  // namespace

RosbagWriter::RosbagWriter(const std::string& path, bool overwrite)
    : file_(path, common::OutputKind::kBag, overwrite) {
  out_.open(file_.temporary(), std::ios::binary | std::ios::trunc);
  if (!out_)
    throw common::InputError(path, "", std::string("cannot write: ") + std::strerror(errno));
  put(kVersionLine);
  put(bagHeaderRecord(0, 0, 0));  // rewritten by close()
}

int RosbagWriter::connect(const std::string& topic, const RosMessageType& type, bool latching) {
  connections_.push_back({topic, type, latching});
  counts_.push_back(0);
  connection_written_.push_back(false);
  return int(connections_.size()) - 1;
}

std::string RosbagWriter::connectionRecord(int id) const {
  const Connection& c = connections_[id];
  const std::string header = field("op", littleEndianBytes(std::uint8_t(kConnection))) +
                             field("conn", littleEndianBytes(std::uint32_t(id))) +
                             field("topic", c.topic);
  std::string data =
      field("topic", c.topic) + field("type", c.type.datatype) + field("md5sum", c.type.md5sum) +
      field("message_definition", c.type.definition) + field("callerid", "/isg_export");
  if (c.latching) data += field("latching", "1");
  return bagRecord(header, data);
}

void RosbagWriter::write(int connection, RosTime time, const std::string& serialised) {
  if (closed_) throw std::logic_error("RosbagWriter::write after close");
  if (chunk_.empty()) chunk_info_ = {position_, time, time, {}};
  if (!connection_written_[connection]) {
    // The first message of a connection is preceded by its record, so that a reader scanning the
    // chunks (rosbag reindex) knows the type.
    chunk_ += connectionRecord(connection);
    connection_written_[connection] = true;
  }
  chunk_index_[connection].push_back({time, std::uint32_t(chunk_.size())});
  const std::string header = field("op", littleEndianBytes(std::uint8_t(kMessageData))) +
                             field("conn", littleEndianBytes(std::uint32_t(connection))) +
                             field("time", timeBytes(time));
  chunk_ += bagRecord(header, serialised);
  if (time < chunk_info_.start) chunk_info_.start = time;
  if (chunk_info_.end < time) chunk_info_.end = time;
  ++chunk_info_.counts[connection];
  ++counts_[connection];
  if (chunk_.size() >= kChunkThreshold) flushChunk();
}

void RosbagWriter::flushChunk() {
  if (chunk_.empty()) return;
  const std::string header = field("op", littleEndianBytes(std::uint8_t(kChunk))) +
                             field("compression", "none") +
                             field("size", littleEndianBytes(std::uint32_t(chunk_.size())));
  put(bagRecord(header, chunk_));
  for (const auto& [connection, entries] : chunk_index_) {
    const std::string index_header =
        field("op", littleEndianBytes(std::uint8_t(kIndexData))) +
        field("ver", littleEndianBytes(std::uint32_t(1))) +
        field("conn", littleEndianBytes(std::uint32_t(connection))) +
        field("count", littleEndianBytes(std::uint32_t(entries.size())));
    std::string data;
    data.reserve(entries.size() * 12);
    for (const IndexEntry& e : entries) data += timeBytes(e.time) + littleEndianBytes(e.offset);
    put(bagRecord(index_header, data));
  }
  chunks_.push_back(chunk_info_);
  chunk_.clear();
  chunk_index_.clear();
}

void RosbagWriter::close() {
  if (closed_) return;
  flushChunk();
  const std::uint64_t index_position = position_;
  for (int id = 0; id < int(connections_.size()); ++id) put(connectionRecord(id));
  for (const ChunkInfo& chunk : chunks_) {
    const std::string header =
        field("op", littleEndianBytes(std::uint8_t(kChunkInfo))) +
        field("ver", littleEndianBytes(std::uint32_t(1))) +
        field("chunk_pos", littleEndianBytes(chunk.position)) +
        field("start_time", timeBytes(chunk.start)) + field("end_time", timeBytes(chunk.end)) +
        field("count", littleEndianBytes(std::uint32_t(chunk.counts.size())));
    std::string data;
    for (const auto& [connection, count] : chunk.counts) {
      data += littleEndianBytes(std::uint32_t(connection)) + littleEndianBytes(count);
    }
    put(bagRecord(header, data));
  }
  out_.seekp(std::streamoff(std::strlen(kVersionLine)));
  out_ << bagHeaderRecord(index_position, std::uint32_t(connections_.size()),
                          std::uint32_t(chunks_.size()));
  out_.close();
  if (!out_) {  // the failed write(2) left its reason in errno (a full disk, a quota)
    throw common::InputError(
        file_.path().string(), "",
        std::string("cannot write: ") + (errno != 0 ? std::strerror(errno) : "write failed"));
  }
  file_.commit();
  closed_ = true;
}

void RosbagWriter::put(const std::string& bytes) {
  out_.write(bytes.data(), std::streamsize(bytes.size()));
  if (!out_)
    throw common::InputError(file_.path().string(), "",
                             std::string("cannot write: ") + std::strerror(errno));
  position_ += bytes.size();
}

}  // namespace isg::formats
