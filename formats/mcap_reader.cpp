#include "formats/mcap_reader.hpp"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "common/input_error.hpp"
#include "formats/decompress.hpp"
#include "formats/file_bytes.hpp"
#include "formats/mcap_format.hpp"
#include "formats/mcap_writer.hpp"

namespace isg::formats {

namespace {

static_assert(std::endian::native == std::endian::little, "MCAP is little-endian");

using mcap::kChannel, mcap::kChunk, mcap::kDataEnd, mcap::kFooter, mcap::kHeader, mcap::kMagic,
    mcap::kMessage, mcap::kRecordHead, mcap::kSchema;

// Reads the fields of one record's content, each checked against what is left.
class ReadFields {
 public:
  ReadFields(std::string_view content, const char* record) : content_(content), record_(record) {}

  template <typename T>
  T number(const char* field) {
    T v;
    std::memcpy(&v, take(sizeof(T), field).data(), sizeof(T));
    return v;
  }
  std::string_view take(std::uint64_t n, const char* field) {
    if (n > content_.size() - at_) {
      throw std::runtime_error(std::string("the ") + record_ + " record ends inside its field `" +
                               field + "` (byte " + std::to_string(at_) + " of " +
                               std::to_string(content_.size()) + ")");
    }
    const std::string_view out = content_.substr(at_, n);
    at_ += n;
    return out;
  }
  std::string string(const char* field) {
    return std::string(take(number<std::uint32_t>(field), field));
  }
  std::map<std::string, std::string> map(const char* field) {
    ReadFields entries(take(number<std::uint32_t>(field), field), record_);
    std::map<std::string, std::string> out;
    while (!entries.done()) {
      std::string key = entries.string(field);
      out[key] = entries.string(field);
    }
    return out;
  }
  std::string_view rest() { return take(content_.size() - at_, "data"); }
  bool done() const { return at_ == content_.size(); }

 private:
  std::string_view content_;
  const char* record_;
  std::size_t at_ = 0;
};

}  // namespace

McapReader::McapReader(const std::string& path) : name_(path), in_(openBinaryFile(path)) { open(); }

McapReader::McapReader(std::string bytes, const std::string& name)
    : name_(name), in_(std::make_unique<std::istringstream>(std::move(bytes))) {
  open();
}

McapReader::~McapReader() = default;

void McapReader::fail(std::uint64_t offset, const std::string& what) const {
  throw common::InputError(name_, "", "byte " + std::to_string(offset) + ": " + what);
}

void McapReader::open() {
  in_->seekg(0, std::ios::end);
  size_ = std::uint64_t(in_->tellg());
  std::string magic;
  if (!readAt(*in_, 0, kMagic.size(), magic) || magic != kMagic) {
    fail(0, "not an MCAP file (it does not begin with MCAP's magic)");
  }
  if (size_ < 2 * kMagic.size() || !readAt(*in_, size_ - kMagic.size(), kMagic.size(), magic) ||
      magic != kMagic) {
    fail(size_,
         "cut short: the file does not end with MCAP's magic (a recording that was not "
         "closed; `mcap recover` mends it)");
  }
  const std::uint64_t end = size_ - kMagic.size();
  std::uint64_t at = kMagic.size();
  bool first = true;
  std::string head, content;
  while (at < end) {
    if (end - at < kRecordHead || !readAt(*in_, at, kRecordHead, head)) {
      fail(at, "a record's opcode and length do not fit before the closing magic");
    }
    const auto opcode = std::uint8_t(head[0]);
    std::uint64_t length;
    std::memcpy(&length, head.data() + 1, 8);
    if (length > end - at - kRecordHead) {
      fail(at, "a record (opcode 0x" + std::string(1, "0123456789abcdef"[opcode >> 4]) +
                   std::string(1, "0123456789abcdef"[opcode & 15]) + ") of " +
                   std::to_string(length) + " bytes, where " +
                   std::to_string(end - at - kRecordHead) + " are left");
    }
    if (first && opcode != kHeader) fail(at, "the first record is not a Header");
    const std::uint64_t content_at = at + kRecordHead;
    if (opcode == kDataEnd || opcode == kFooter) break;  // the summary is not needed
    // Messages at the top level are read where they lie when asked for; everything else that
    // matters is small, or is a chunk to be indexed now.
    if (opcode == kHeader || opcode == kSchema || opcode == kChannel || opcode == kChunk ||
        opcode == kMessage) {
      const std::uint64_t wanted =
          opcode == kMessage ? std::min<std::uint64_t>(length, 22) : length;
      if (!readAt(*in_, content_at, wanted, content)) fail(at, "cannot read the record");
      try {
        if (opcode == kHeader) {
          if (!first) fail(at, "a second Header");
          ReadFields fields(content, "Header");
          profile_ = fields.string("profile");
          library_ = fields.string("library");
        } else if (opcode == kChunk) {
          readChunk(content, at);
        } else if (opcode == kMessage) {
          if (length < 22) {
            fail(at, "a Message record of " + std::to_string(length) + " bytes (at least 22)");
          }
          readRecord(opcode, content, at, kNoChunk);
        } else {
          readRecord(opcode, content, at, kNoChunk);
        }
      } catch (const std::runtime_error& e) {
        if (dynamic_cast<const common::InputError*>(&e) != nullptr) throw;
        fail(at, e.what());
      }
    }
    first = false;
    at = content_at + length;
  }
  if (first) fail(kMagic.size(), "no Header record");
  // Each message's channel, now that every Channel record has been read.
  for (Entry& entry : entries_) {
    const auto found = channel_index_.find(std::uint16_t(entry.channel));
    if (found == channel_index_.end()) {
      const std::uint64_t where =
          entry.chunk == kNoChunk ? entry.position : chunks_[entry.chunk].position;
      fail(where, "a message on channel " + std::to_string(entry.channel) +
                      ", which no Channel record defines");
    }
    entry.channel = found->second;
    ++channels_[entry.channel].messages;
  }
  std::stable_sort(entries_.begin(), entries_.end(),
                   [](const Entry& a, const Entry& b) { return a.log_time < b.log_time; });
}

void McapReader::readRecord(std::uint8_t opcode, std::string_view content, std::uint64_t offset,
                            std::uint32_t chunk) {
  if (opcode == kSchema) {
    ReadFields fields(content, "Schema");
    const auto id = fields.number<std::uint16_t>("id");
    SchemaRecord schema;
    schema.name = fields.string("name");
    schema.encoding = fields.string("encoding");
    schema.data = fields.string("data");
    if (id == 0) throw std::runtime_error("a Schema with id 0 (reserved for \"no schema\")");
    const auto [it, added] = schemas_.emplace(id, schema);
    if (!added && (it->second.name != schema.name || it->second.data != schema.data)) {
      throw std::runtime_error("schema " + std::to_string(id) + " is defined twice, differently");
    }
  } else if (opcode == kChannel) {
    ReadFields fields(content, "Channel");
    McapChannel channel;
    channel.id = fields.number<std::uint16_t>("id");
    const auto schema_id = fields.number<std::uint16_t>("schema_id");
    channel.topic = fields.string("topic");
    channel.message_encoding = fields.string("message_encoding");
    channel.metadata = fields.map("metadata");
    if (schema_id != 0) {
      const auto schema = schemas_.find(schema_id);
      if (schema == schemas_.end()) {
        throw std::runtime_error("channel " + std::to_string(channel.id) + " (" + channel.topic +
                                 ") names schema " + std::to_string(schema_id) +
                                 ", which no Schema record before it defines");
      }
      channel.schema_name = schema->second.name;
      channel.schema_encoding = schema->second.encoding;
      channel.schema_data = schema->second.data;
    }
    const auto known = channel_index_.find(channel.id);
    if (known != channel_index_.end()) {
      const McapChannel& before = channels_[known->second];
      if (before.topic != channel.topic || before.schema_name != channel.schema_name ||
          before.message_encoding != channel.message_encoding) {
        throw std::runtime_error("channel " + std::to_string(channel.id) +
                                 " is defined twice, differently (" + before.topic + ", then " +
                                 channel.topic + ")");
      }
      return;
    }
    channel_index_.emplace(channel.id, std::uint32_t(channels_.size()));
    channels_.push_back(std::move(channel));
  } else if (opcode == kMessage) {
    ReadFields fields(content, "Message");
    Entry entry;
    entry.channel = fields.number<std::uint16_t>("channel_id");
    fields.number<std::uint32_t>("sequence");
    entry.log_time = fields.number<std::uint64_t>("log_time");
    entry.position = offset;
    entry.chunk = chunk;
    entries_.push_back(entry);
  }
}

void McapReader::readChunk(std::string_view content, std::uint64_t position) {
  ReadFields fields(content, "Chunk");
  fields.number<std::uint64_t>("message_start_time");
  fields.number<std::uint64_t>("message_end_time");
  Chunk chunk;
  chunk.position = position;
  chunk.size = fields.number<std::uint64_t>("uncompressed_size");
  chunk.crc = fields.number<std::uint32_t>("uncompressed_crc");
  chunk.compression = fields.string("compression");
  if (chunk.compression.empty()) chunk.compression = "none";
  const auto records_length = fields.number<std::uint64_t>("records");
  const std::string_view records = fields.take(records_length, "records");
  chunk.data_offset = position + kRecordHead + std::uint64_t(records.data() - content.data());
  chunk.data_size = records.size();
  if (chunk.compression != "none" && chunk.compression != "zstd" && chunk.compression != "lz4") {
    throw std::runtime_error("a chunk compressed with \"" + chunk.compression +
                             "\" (MCAP names \"zstd\" and \"lz4\")");
  }
  if (chunk.size > kMaxChunkBytes) {
    throw std::runtime_error("a chunk of " + std::to_string(chunk.size) +
                             " bytes uncompressed; at most " + std::to_string(kMaxChunkBytes) +
                             " are read (docs/formats.md, \"Limits of recordings\")");
  }
  if (std::find(compressions_.begin(), compressions_.end(), chunk.compression) ==
      compressions_.end()) {
    compressions_.push_back(chunk.compression);
  }
  const auto k = std::uint32_t(chunks_.size());
  chunks_.push_back(chunk);
  const std::string& bytes = loadChunk(k);
  std::uint64_t at = 0;
  while (at < bytes.size()) {
    if (bytes.size() - at < kRecordHead) {
      throw std::runtime_error("its records end inside a record's opcode and length (byte " +
                               std::to_string(at) + " of " + std::to_string(bytes.size()) +
                               " uncompressed)");
    }
    const auto opcode = std::uint8_t(bytes[at]);
    std::uint64_t length;
    std::memcpy(&length, bytes.data() + at + 1, 8);
    if (length > bytes.size() - at - kRecordHead) {
      throw std::runtime_error("a record at byte " + std::to_string(at) + " of its " +
                               std::to_string(bytes.size()) + " uncompressed bytes claims " +
                               std::to_string(length));
    }
    const std::string_view inner(bytes.data() + at + kRecordHead, length);
    if (opcode == kMessage && length < 22) {
      throw std::runtime_error("a Message record of " + std::to_string(length) +
                               " bytes (at least 22) at byte " + std::to_string(at) +
                               " of its records");
    }
    if (opcode == kSchema || opcode == kChannel || opcode == kMessage) {
      readRecord(opcode, inner, at, k);
    }
    at += kRecordHead + length;
  }
}

const std::string& McapReader::loadChunk(std::uint32_t k) {
  if (const std::string* held = cache_.find(k)) return *held;
  const Chunk& chunk = chunks_[k];
  cache_.makeRoom(chunk.size);
  std::string stored;
  if (!readAt(*in_, chunk.data_offset, chunk.data_size, stored)) {
    fail(chunk.position, "cannot read the chunk's records");
  }
  std::string bytes;
  if (chunk.compression == "none") {
    if (stored.size() != chunk.size) {
      fail(chunk.position, "an uncompressed chunk of " + std::to_string(stored.size()) +
                               " bytes that says it holds " + std::to_string(chunk.size));
    }
    bytes = std::move(stored);
  } else {
    std::string error;
    if (!decompress(chunk.compression, stored, chunk.size, bytes, error)) {
      fail(chunk.position, "the " + chunk.compression + " chunk does not decompress to its " +
                               std::to_string(chunk.size) + " bytes: " + error);
    }
  }
  if (chunk.crc != 0 && crc32(bytes) != chunk.crc) {
    fail(chunk.position, "the chunk's records fail their CRC-32");
  }
  return cache_.insert(k, std::move(bytes));
}

void McapReader::read(const std::vector<std::string>& topics,
                      const std::function<bool(const McapMessageView&)>& visit) {
  std::vector<bool> wanted(channels_.size(), topics.empty());
  for (std::size_t c = 0; c < channels_.size(); ++c) {
    if (std::find(topics.begin(), topics.end(), channels_[c].topic) != topics.end()) {
      wanted[c] = true;
    }
  }
  std::uint64_t index = 0;
  std::string top_level;
  for (const Entry& entry : entries_) {
    if (!wanted[entry.channel]) continue;
    std::string_view record;
    if (entry.chunk == kNoChunk) {
      std::string head;
      if (!readAt(*in_, entry.position, kRecordHead, head)) fail(entry.position, "cannot read");
      std::uint64_t length;
      std::memcpy(&length, head.data() + 1, 8);
      if (!readAt(*in_, entry.position + kRecordHead, length, top_level)) {
        fail(entry.position, "cannot read the message");
      }
      record = top_level;
    } else {
      const std::string& bytes = loadChunk(entry.chunk);
      std::uint64_t length;
      std::memcpy(&length, bytes.data() + entry.position + 1, 8);
      record = std::string_view(bytes).substr(entry.position + kRecordHead, length);
    }
    McapMessageView view;
    view.channel = &channels_[entry.channel];
    std::memcpy(&view.sequence, record.data() + 2, 4);
    view.log_time_ns = entry.log_time;
    std::memcpy(&view.publish_time_ns, record.data() + 14, 8);
    view.data = record.substr(22);
    view.index = index++;
    view.record_offset = entry.position;
    view.chunk_offset = entry.chunk == kNoChunk ? 0 : chunks_[entry.chunk].position;
    if (!visit(view)) return;
  }
}

}  // namespace isg::formats
