#include "formats/rosbag_reader.hpp"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "common/input_error.hpp"
#include "formats/decompress.hpp"
#include "formats/file_bytes.hpp"
#include "formats/rosbag_format.hpp"

namespace isg::formats {

namespace {

static_assert(std::endian::native == std::endian::little, "the format is little-endian");

// A record's header: its fields by name (values are bytes).
using HeaderFields = std::map<std::string, std::string, std::less<>>;

// The fields of a header block; nullopt-like empty name on a malformed block is reported by the
// caller through `error`.
bool parseFields(std::string_view block, HeaderFields& fields, std::string& error) {
  std::size_t at = 0;
  while (at < block.size()) {
    if (block.size() - at < 4) {
      error = "a header field's length is cut off";
      return false;
    }
    std::uint32_t length;
    std::memcpy(&length, block.data() + at, 4);
    at += 4;
    if (length > block.size() - at) {
      error = "a header field runs past its header (" + std::to_string(length) + " bytes)";
      return false;
    }
    const std::string_view field = block.substr(at, length);
    at += length;
    const std::size_t equals = field.find('=');
    if (equals == std::string_view::npos) {
      error = "a header field has no '='";
      return false;
    }
    fields.emplace(std::string(field.substr(0, equals)), std::string(field.substr(equals + 1)));
  }
  return true;
}

template <typename T>
bool fieldValue(const HeaderFields& fields, std::string_view name, T& value) {
  const auto it = fields.find(name);
  if (it == fields.end() || it->second.size() != sizeof(T)) return false;
  std::memcpy(&value, it->second.data(), sizeof(T));
  return true;
}

bool timeValue(const HeaderFields& fields, std::string_view name, RosTime& time) {
  std::uint64_t both;
  if (!fieldValue(fields, name, both)) return false;
  time.sec = std::uint32_t(both & 0xffffffffu);
  time.nsec = std::uint32_t(both >> 32);
  return true;
}

const char* opName(std::uint8_t op) {
  switch (op) {
    case rosbag::kMessageData:
      return "message data";
    case rosbag::kBagHeader:
      return "bag header";
    case rosbag::kIndexData:
      return "index data";
    case rosbag::kChunk:
      return "chunk";
    case rosbag::kChunkInfo:
      return "chunk info";
    case rosbag::kConnection:
      return "connection";
  }
  return "unknown";
}

std::string hexOp(std::uint8_t op) {
  char text[8];
  std::snprintf(text, sizeof text, "0x%02x", unsigned(op));
  return text;
}

// A record read from the file or from a chunk: its header's fields and where its data lies.
struct RecordAt {
  HeaderFields fields;
  std::uint8_t op = 0;
  std::uint64_t data_offset = 0;
  std::uint32_t data_size = 0;
  std::uint64_t end = 0;  // just past the record
};

// What a record's two readers share, once its header block and data length are read: the
// header's fields, the data's place (`data_available` bytes follow the length; `beyond` ends
// the message when the data does not fit) and the op.
bool completeRecord(std::string_view header, std::uint32_t data_size, std::uint64_t data_offset,
                    std::uint64_t data_available, const std::string& beyond, RecordAt& record,
                    std::string& error) {
  if (!parseFields(header, record.fields, error)) return false;
  record.data_size = data_size;
  if (data_size > data_available) {
    error = "the record's data runs past the end" + beyond;
    return false;
  }
  record.data_offset = data_offset;
  record.end = data_offset + data_size;
  if (!fieldValue(record.fields, "op", record.op)) {
    error = "the record has no one-byte op field";
    return false;
  }
  return true;
}

// Reads the record at `offset` of `bytes` (a chunk), or fails with `error`.
bool recordIn(std::string_view bytes, std::uint64_t offset, RecordAt& record, std::string& error) {
  if (offset > bytes.size() || bytes.size() - offset < 4) {
    error = "the record is cut off";
    return false;
  }
  std::uint32_t header_size;
  std::memcpy(&header_size, bytes.data() + offset, 4);
  const std::uint64_t at = offset + 4;
  if (header_size > bytes.size() - at || bytes.size() - at - header_size < 4) {
    error = "the record's header runs past the end (" + std::to_string(header_size) + " bytes)";
    return false;
  }
  std::uint32_t data_size;
  std::memcpy(&data_size, bytes.data() + at + header_size, 4);
  const std::uint64_t data_offset = at + header_size + 4;
  return completeRecord(bytes.substr(at, header_size), data_size, data_offset,
                        bytes.size() - data_offset, " (" + std::to_string(data_size) + " bytes)",
                        record, error);
}

// Reads `size` bytes at `offset` of the stream, or returns false.
// Reads the header of the record at `offset` of a file of `file_size` bytes (not its data), or
// fails with `error`.
bool fileRecord(std::istream& in, std::uint64_t file_size, std::uint64_t offset, RecordAt& record,
                std::string& error) {
  std::string head;
  std::uint32_t header_size = 0;
  if (offset > file_size || !readAt(in, offset, 4, head)) {
    error = "the file ends inside a record (truncated?)";
    return false;
  }
  std::memcpy(&header_size, head.data(), 4);
  if (header_size > file_size - offset - 4 || file_size - offset - 4 - header_size < 4) {
    error = "the record's header runs past the end of the file (truncated?)";
    return false;
  }
  std::string header;
  readAt(in, offset + 4, header_size + 4, header);
  std::uint32_t data_size;
  std::memcpy(&data_size, header.data() + header_size, 4);
  const std::uint64_t data_offset = offset + 8 + header_size;
  return completeRecord(std::string_view(header).substr(0, header_size), data_size, data_offset,
                        file_size - data_offset, " of the file (truncated?)", record, error);
}

}  // namespace

RosbagReader::RosbagReader(const std::string& path) : name_(path), in_(openBinaryFile(path)) {
  open();
}

RosbagReader::RosbagReader(std::string bytes, const std::string& name)
    : name_(name), in_(std::make_unique<std::istringstream>(std::move(bytes))) {
  open();
}

RosbagReader::~RosbagReader() = default;

void RosbagReader::fail(std::uint64_t offset, const std::string& what) const {
  throw common::InputError(name_, "", "byte " + std::to_string(offset) + ": " + what);
}

void RosbagReader::open() {
  in_->seekg(0, std::ios::end);
  size_ = std::uint64_t(in_->tellg());
  std::string version;
  const std::size_t version_size = std::strlen(rosbag::kVersionLine);
  if (!readAt(*in_, 0, version_size, version) || version != rosbag::kVersionLine) {
    if (version.rfind("#ROSBAG V", 0) == 0) {
      const std::string line = version.substr(0, version.find('\n'));
      throw common::InputError(name_, "",
                               "a ROS bag of version " + line.substr(9) +
                                   ": only version 2.0 is read (rosbag fix converts older bags)");
    }
    throw common::InputError(name_, "", "not a ROS 1 bag: it does not start with \"#ROSBAG V2.0\"");
  }
  RecordAt header;
  std::string error;
  if (!fileRecord(*in_, size_, version_size, header, error)) fail(version_size, error);
  if (header.op != rosbag::kBagHeader)
    fail(version_size, std::string("expected the bag header record, found a ") + opName(header.op) +
                           " record (op " + hexOp(header.op) + ")");
  std::uint64_t index_position = 0;
  std::uint32_t connection_count = 0, chunk_count = 0;
  if (!fieldValue(header.fields, "index_pos", index_position) ||
      !fieldValue(header.fields, "conn_count", connection_count) ||
      !fieldValue(header.fields, "chunk_count", chunk_count))
    fail(version_size, "the bag header lacks index_pos, conn_count or chunk_count");
  if (index_position == 0)
    throw common::InputError(
        name_, "",
        "the bag is not indexed (its recording was cut short): `rosbag reindex` "
        "mends it");
  if (index_position < header.end || index_position > size_)
    fail(version_size, "the bag header's index position " + std::to_string(index_position) +
                           " lies outside the file (truncated?)");
  readIndex(index_position, connection_count, chunk_count);
}

namespace {

// The next record of the bag's index, at `at` in its bytes, which must be of kind `expected`.
template <typename Fail>
RecordAt indexRecord(const std::string& bytes, std::uint64_t index_position, std::uint64_t at,
                     std::uint8_t expected, const Fail& fail) {
  RecordAt record;
  std::string error;
  if (!recordIn(bytes, at, record, error)) fail(index_position + at, error);
  if (record.op != expected)
    fail(index_position + at, std::string("expected a ") + opName(expected) +
                                  " record in the bag's index, found a " + opName(record.op) +
                                  " record (op " + hexOp(record.op) + ")");
  return record;
}

// A connection record of the index (at byte `offset` of the file): its number, topic and type.
template <typename Fail>
BagConnection connectionOf(const RecordAt& record, const std::string& bytes, std::uint64_t offset,
                           const Fail& fail) {
  BagConnection c;
  if (!fieldValue(record.fields, "conn", c.id)) fail(offset, "a connection without conn");
  HeaderFields data;
  std::string error;
  if (!parseFields(std::string_view(bytes).substr(record.data_offset, record.data_size), data,
                   error))
    fail(offset, "connection " + std::to_string(c.id) + ": " + error);
  auto text = [&](const char* name, bool required) {
    const auto it = data.find(std::string_view(name));
    if (it == data.end()) {
      if (required)
        fail(offset, "connection " + std::to_string(c.id) + " has no " + name + " field");
      return std::string();
    }
    return it->second;
  };
  const auto topic = record.fields.find(std::string_view("topic"));
  c.topic = topic != record.fields.end() ? topic->second : text("topic", true);
  c.type.datatype = text("type", true);
  c.type.md5sum = text("md5sum", true);
  c.type.definition = text("message_definition", false);
  c.callerid = text("callerid", false);
  c.latching = text("latching", false) == "1";
  return c;
}

// A chunk info record of the index: where its chunk is, its count per connection number (the
// last given for a number), and the messages it adds to each (every count given).
struct ChunkInfo {
  std::uint64_t position = 0;
  std::map<std::uint32_t, std::uint32_t> counts;
  std::map<std::uint32_t, std::uint64_t> messages;
};

template <typename Fail>
ChunkInfo chunkInfoOf(const RecordAt& record, const std::string& bytes, std::uint64_t offset,
                      const std::map<std::uint32_t, std::size_t>& connection_by_id,
                      const Fail& fail) {
  ChunkInfo info;
  std::uint32_t version = 0, count = 0;
  if (!fieldValue(record.fields, "ver", version) || version != 1)
    fail(offset, "a chunk info record of a version other than 1");
  if (!fieldValue(record.fields, "chunk_pos", info.position) ||
      !fieldValue(record.fields, "count", count))
    fail(offset, "a chunk info without chunk_pos or count");
  if (record.data_size != std::uint64_t(count) * 8)
    fail(offset, "a chunk info's data is not its " + std::to_string(count) + " counts");
  for (std::uint32_t k = 0; k < count; ++k) {
    std::uint32_t pair[2];
    std::memcpy(pair, bytes.data() + record.data_offset + 8 * k, 8);
    if (!connection_by_id.count(pair[0]))
      fail(offset, "a chunk info names connection " + std::to_string(pair[0]) +
                       ", which the bag does not define");
    info.counts[pair[0]] = pair[1];
    info.messages[pair[0]] += pair[1];
  }
  return info;
}

}  // namespace

void RosbagReader::readIndex(std::uint64_t index_position, std::uint32_t connection_count,
                             std::uint32_t chunk_count) {
  std::string bytes;
  if (!readAt(*in_, index_position, std::size_t(size_ - index_position), bytes))
    fail(index_position, "cannot read the bag's index");
  const auto failAt = [this](std::uint64_t offset, const std::string& what) { fail(offset, what); };
  std::map<std::uint32_t, std::size_t> connection_by_id;
  std::vector<std::size_t> chunk_connections;  // per chunk: how many connections it holds
  std::uint64_t at = 0;
  for (std::uint32_t i = 0; i < connection_count; ++i) {
    const std::uint64_t offset = index_position + at;
    const RecordAt record = indexRecord(bytes, index_position, at, rosbag::kConnection, failAt);
    BagConnection c = connectionOf(record, bytes, offset, failAt);
    if (!connection_by_id.emplace(c.id, connections_.size()).second)
      fail(offset, "connection " + std::to_string(c.id) + " is defined twice");
    connections_.push_back(std::move(c));
    at = record.end;
  }
  for (std::uint32_t i = 0; i < chunk_count; ++i) {
    const std::uint64_t offset = index_position + at;
    const RecordAt record = indexRecord(bytes, index_position, at, rosbag::kChunkInfo, failAt);
    const ChunkInfo info = chunkInfoOf(record, bytes, offset, connection_by_id, failAt);
    for (const auto& [connection, messages] : info.messages) {
      connections_[connection_by_id[connection]].messages += messages;
    }
    Chunk chunk;
    chunk.position = info.position;
    chunks_.push_back(chunk);
    chunk_connections.push_back(info.counts.size());
    at = record.end;
  }
  // Each chunk's record and the index records that follow it: every message's time and place.
  for (std::uint32_t k = 0; k < chunks_.size(); ++k) {
    readChunkRecord(k, index_position);
    readChunkIndex(k, std::uint32_t(chunk_connections[k]));
  }
  // Which connection each entry is, as an index into connections_.
  for (Entry& e : entries_) {
    const auto it = connection_by_id.find(e.connection);
    if (it == connection_by_id.end())
      fail(chunks_[e.chunk].position, "an index record names connection " +
                                          std::to_string(e.connection) +
                                          ", which the bag does not define");
    e.connection = std::uint32_t(it->second);
  }
  // Time order; ties by connection number, then in the bag's order, as rosbag's reader merges its
  // connections' indexes.
  std::stable_sort(entries_.begin(), entries_.end(), [this](const Entry& a, const Entry& b) {
    if (a.time < b.time || b.time < a.time) return a.time < b.time;
    return connections_[a.connection].id < connections_[b.connection].id;
  });
}

void RosbagReader::readChunkRecord(std::uint32_t k, std::uint64_t index_position) {
  Chunk& chunk = chunks_[k];
  const std::uint64_t position = chunk.position;
  if (position < std::strlen(rosbag::kVersionLine) || position >= size_)
    fail(index_position,
         "a chunk info points outside the file (byte " + std::to_string(position) + ")");
  RecordAt record;
  std::string error;
  if (!fileRecord(*in_, size_, position, record, error)) fail(position, error);
  if (record.op != rosbag::kChunk)
    fail(position, "a chunk info points at a record that is not a chunk");
  const auto compression = record.fields.find(std::string_view("compression"));
  if (compression == record.fields.end() || !fieldValue(record.fields, "size", chunk.size))
    fail(position, "a chunk without compression or size");
  if (chunk.size > kMaxChunkBytes)
    fail(position, "a chunk of " + std::to_string(chunk.size) + " bytes uncompressed; at most " +
                       std::to_string(kMaxChunkBytes) +
                       " are read (docs/formats.md, \"Limits of recordings\")");
  chunk.compression = compression->second;
  if (chunk.compression != "none" && chunk.compression != "bz2" && chunk.compression != "lz4")
    fail(position, "chunk compression \"" + chunk.compression +
                       "\" is not supported (none, bz2 and lz4 are)");
  if (std::find(compressions_.begin(), compressions_.end(), chunk.compression) ==
      compressions_.end())
    compressions_.push_back(chunk.compression);
  chunk.data_offset = record.data_offset;
  chunk.data_size = record.data_size;
}

void RosbagReader::readChunkIndex(std::uint32_t k, std::uint32_t index_records) {
  const Chunk& chunk = chunks_[k];
  std::uint64_t offset = chunk.data_offset + chunk.data_size;
  for (std::uint32_t i = 0; i < index_records; ++i) {
    RecordAt record;
    std::string error;
    if (!fileRecord(*in_, size_, offset, record, error)) fail(offset, error);
    std::uint32_t version = 0, connection = 0, count = 0;
    if (record.op != rosbag::kIndexData)
      fail(offset, "expected an index data record after the chunk");
    if (!fieldValue(record.fields, "ver", version) || version != 1 ||
        !fieldValue(record.fields, "conn", connection) ||
        !fieldValue(record.fields, "count", count))
      fail(offset, "an index data record without ver 1, conn or count");
    if (record.data_size != std::uint64_t(count) * 12)
      fail(offset, "an index data record's data is not its " + std::to_string(count) + " entries");
    std::string data;
    if (!readAt(*in_, record.data_offset, record.data_size, data))
      fail(offset, "the file ends inside an index data record");
    for (std::uint32_t j = 0; j < count; ++j) {
      Entry e;
      std::memcpy(&e.time.sec, data.data() + 12 * j, 4);
      std::memcpy(&e.time.nsec, data.data() + 12 * j + 4, 4);
      std::memcpy(&e.offset, data.data() + 12 * j + 8, 4);
      if (e.offset >= chunk.size)
        fail(offset,
             "an index entry points past its chunk's " + std::to_string(chunk.size) + " bytes");
      e.chunk = k;
      e.connection = connection;
      entries_.push_back(e);
    }
    offset = record.end;
  }
}

const std::string& RosbagReader::loadChunk(std::uint32_t k) {
  if (const std::string* held = cache_.find(k)) return *held;
  const Chunk& chunk = chunks_[k];
  cache_.makeRoom(chunk.size);
  std::string stored;
  if (!readAt(*in_, chunk.data_offset, chunk.data_size, stored))
    fail(chunk.position, "cannot read the chunk's data");
  std::string bytes;
  if (chunk.compression == "none") {
    if (stored.size() != chunk.size)
      fail(chunk.position, "an uncompressed chunk of " + std::to_string(stored.size()) +
                               " bytes says it holds " + std::to_string(chunk.size));
    bytes = std::move(stored);
  } else {
    std::string error;
    if (!decompress(chunk.compression, stored, chunk.size, bytes, error))
      fail(chunk.position, "the " + chunk.compression + " chunk does not decompress to its " +
                               std::to_string(chunk.size) + " bytes (" + error + ")");
  }
  return cache_.insert(k, std::move(bytes));
}

RosTime RosbagReader::startTime() const {
  return entries_.empty() ? RosTime{} : entries_.front().time;
}

RosTime RosbagReader::endTime() const {
  return entries_.empty() ? RosTime{} : entries_.back().time;
}

void RosbagReader::read(const std::vector<std::string>& topics,
                        const std::function<bool(const BagMessageView&)>& visit) {
  std::vector<char> wanted(connections_.size(), topics.empty());
  for (std::size_t i = 0; i < connections_.size(); ++i) {
    if (std::find(topics.begin(), topics.end(), connections_[i].topic) != topics.end())
      wanted[i] = 1;
  }
  std::uint64_t index = 0;
  for (const Entry& e : entries_) {
    if (!wanted[e.connection]) continue;
    const std::string& chunk = loadChunk(e.chunk);
    RecordAt record;
    std::string error;
    const std::uint64_t where = chunks_[e.chunk].position;
    if (!recordIn(chunk, e.offset, record, error))
      fail(where, "chunk byte " + std::to_string(e.offset) + ": " + error);
    std::uint32_t connection = 0;
    RosTime time;
    if (record.op != rosbag::kMessageData || !fieldValue(record.fields, "conn", connection) ||
        !timeValue(record.fields, "time", time))
      fail(where, "chunk byte " + std::to_string(e.offset) +
                      ": the index points at a record that is not a message");
    if (connection != connections_[e.connection].id)
      fail(where, "chunk byte " + std::to_string(e.offset) + ": a message of connection " +
                      std::to_string(connection) + " indexed under connection " +
                      std::to_string(connections_[e.connection].id));
    BagMessageView view;
    view.connection = &connections_[e.connection];
    view.time = e.time;
    view.data = std::string_view(chunk).substr(record.data_offset, record.data_size);
    view.index = index++;
    if (!visit(view)) return;
  }
}

}  // namespace isg::formats
