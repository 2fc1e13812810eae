#include "formats/mcap_writer.hpp"

#include <lz4frame.h>
#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "common/input_error.hpp"
#include "common/output_path.hpp"
#include "formats/mcap_format.hpp"

namespace isg::formats {

namespace {

// A write that failed, with the reason the failed write(2) left in errno (a full disk, a quota).
common::InputError writeFailure(const std::string& path) {
  return common::InputError(
      path, "",
      std::string("cannot write: ") + (errno != 0 ? std::strerror(errno) : "write failed"));
}

static_assert(std::endian::native == std::endian::little,
              "MCAP here is written as the host lays it");

using mcap::kChannel, mcap::kChunk, mcap::kChunkIndex, mcap::kDataEnd, mcap::kFooter, mcap::kHeader,
    mcap::kMessage, mcap::kMessageIndex, mcap::kSchema, mcap::kStatistics, mcap::kSummaryOffset;
using mcap::Opcode;
const std::string kMagic(mcap::kMagic);

// Little-endian fields, strings and maps as the MCAP specification lays them out.
class WriteFields {
 public:
  template <typename T>
  WriteFields& number(T v) {
    bytes_.append(reinterpret_cast<const char*>(&v), sizeof v);
    return *this;
  }
  WriteFields& string(const std::string& s) {
    number(std::uint32_t(s.size()));
    bytes_.append(s);
    return *this;
  }
  WriteFields& raw(const std::string& s) {
    bytes_.append(s);
    return *this;
  }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

std::string mcapRecord(Opcode opcode, const std::string& content) {
  WriteFields r;
  r.number(std::uint8_t(opcode)).number(std::uint64_t(content.size())).raw(content);
  return r.bytes();
}

std::string schemaRecord(std::uint16_t id, const std::string& name, const std::string& encoding,
                         const std::string& data) {
  WriteFields f;
  f.number(id).string(name).string(encoding).string(data);
  return mcapRecord(kSchema, f.bytes());
}

std::string compress(McapCompression compression, const std::string& data,
                     const std::string& path) {
  std::string out;
  if (compression == McapCompression::kZstd) {
    out.resize(ZSTD_compressBound(data.size()));
    const std::size_t size = ZSTD_compress(out.data(), out.size(), data.data(), data.size(), 3);
    if (ZSTD_isError(size)) {
      throw common::InputError(path, "", std::string("zstd: ") + ZSTD_getErrorName(size));
    }
    out.resize(size);
  } else {
    LZ4F_preferences_t preferences;
    std::memset(&preferences, 0, sizeof preferences);
    preferences.frameInfo.contentSize = data.size();
    out.resize(LZ4F_compressFrameBound(data.size(), &preferences));
    const std::size_t size =
        LZ4F_compressFrame(out.data(), out.size(), data.data(), data.size(), &preferences);
    if (LZ4F_isError(size)) {
      throw common::InputError(path, "", std::string("lz4: ") + LZ4F_getErrorName(size));
    }
    out.resize(size);
  }
  return out;
}

}  // namespace

std::uint32_t crc32(const std::string& bytes, std::uint32_t crc) {
  return std::uint32_t(::crc32_z(crc, reinterpret_cast<const Bytef*>(bytes.data()), bytes.size()));
}

const char* compressionName(McapCompression compression) {
  switch (compression) {
    case McapCompression::kZstd:
      return "zstd";
    case McapCompression::kLz4:
      return "lz4";
    default:
      return "none";
  }
}

McapWriter::McapWriter(const std::string& path, const McapWriterOptions& options)
    : options_(options), file_(path, common::OutputKind::kMcap, options.overwrite), data_crc_(0) {
  out_.open(file_.temporary(), std::ios::binary | std::ios::trunc);
  if (!out_)
    throw common::InputError(path, "", std::string("cannot write: ") + std::strerror(errno));
  WriteFields header;
  header.string(options_.profile).string(std::string("isg (") + common::kWrittenByIsg + ")");
  put(kMagic);
  put(mcapRecord(kHeader, header.bytes()));
}

std::uint16_t McapWriter::addSchema(const std::string& name, const std::string& encoding,
                                    const std::string& data) {
  schemas_.push_back({name, encoding, data});
  schema_in_chunk_.push_back(false);
  return std::uint16_t(schemas_.size());  // 0 is "no schema"
}

std::uint16_t McapWriter::addChannel(std::uint16_t schema, const std::string& topic,
                                     const std::string& message_encoding,
                                     const std::map<std::string, std::string>& metadata) {
  channels_.push_back({schema, topic, message_encoding, metadata});
  channel_in_chunk_.push_back(false);
  counts_.push_back(0);
  return std::uint16_t(channels_.size() - 1);
}

namespace {

std::string channelRecord(std::uint16_t id, std::uint16_t schema, const std::string& topic,
                          const std::string& encoding,
                          const std::map<std::string, std::string>& metadata) {
  WriteFields map;
  for (const auto& [key, value] : metadata) map.string(key).string(value);
  WriteFields f;
  f.number(id).number(schema).string(topic).string(encoding).string(map.bytes());
  return mcapRecord(kChannel, f.bytes());
}

}  // namespace

void McapWriter::write(std::uint16_t channel, std::uint64_t log_time_ns, const std::string& data) {
  if (closed_) throw std::logic_error("McapWriter::write after close");
  const Channel& c = channels_.at(channel);
  // A chunk declares what its messages need, so that it reads on its own.
  if (c.schema > 0 && !schema_in_chunk_[c.schema - 1]) {
    const Schema& s = schemas_[c.schema - 1];
    chunk_ += schemaRecord(c.schema, s.name, s.encoding, s.data);
    schema_in_chunk_[c.schema - 1] = true;
  }
  if (!channel_in_chunk_[channel]) {
    chunk_ += channelRecord(channel, c.schema, c.topic, c.message_encoding, c.metadata);
    channel_in_chunk_[channel] = true;
  }
  const bool first_in_chunk = chunk_messages_.empty();
  chunk_messages_[channel].emplace_back(log_time_ns, chunk_.size());
  // The record's head, then the data as it is (a cloud is most of the file: copied once).
  WriteFields head;
  head.number(std::uint8_t(kMessage))
      .number(std::uint64_t(2 + 4 + 8 + 8 + data.size()))
      .number(channel)
      .number(std::uint32_t(counts_[channel]))
      .number(log_time_ns)   // log time
      .number(log_time_ns);  // publish time
  chunk_ += head.bytes();
  chunk_ += data;
  chunk_start_ = first_in_chunk ? log_time_ns : std::min(chunk_start_, log_time_ns);
  chunk_end_ = first_in_chunk ? log_time_ns : std::max(chunk_end_, log_time_ns);
  message_start_ = messages_ == 0 ? log_time_ns : std::min(message_start_, log_time_ns);
  message_end_ = messages_ == 0 ? log_time_ns : std::max(message_end_, log_time_ns);
  ++messages_;
  ++counts_[channel];
  if (chunk_.size() >= options_.chunk_size) flushChunk();
}

std::string McapWriter::chunkCompression() const {
  return options_.compression == McapCompression::kNone ? ""
                                                        : compressionName(options_.compression);
}

void McapWriter::flushChunk() {
  if (chunk_messages_.empty()) return;
  ChunkIndex index;
  index.start = chunk_start_;
  index.end = chunk_end_;
  index.offset = position_;
  index.uncompressed_size = chunk_.size();
  const std::string compressed =
      options_.compression == McapCompression::kNone
          ? std::string()
          : compress(options_.compression, chunk_, file_.path().string());
  const std::string& records = options_.compression == McapCompression::kNone ? chunk_ : compressed;
  index.compressed_size = records.size();
  WriteFields head;
  head.number(chunk_start_)
      .number(chunk_end_)
      .number(std::uint64_t(chunk_.size()))
      .number(crc32(chunk_))
      .string(chunkCompression())
      .number(std::uint64_t(records.size()));
  WriteFields opcode;
  opcode.number(std::uint8_t(kChunk)).number(std::uint64_t(head.bytes().size() + records.size()));
  put(opcode.bytes() + head.bytes());
  put(records);
  index.length = position_ - index.offset;
  const std::uint64_t indexes_start = position_;
  for (auto& [channel, entries] : chunk_messages_) {
    // By log time, as readers expect of an index; messages written out of order keep their order
    // among equal times.
    std::stable_sort(entries.begin(), entries.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    WriteFields entries_bytes;
    for (const auto& [time, offset] : entries) entries_bytes.number(time).number(offset);
    WriteFields m;
    m.number(channel).string(entries_bytes.bytes());
    index.message_index_offsets[channel] = position_;
    put(mcapRecord(kMessageIndex, m.bytes()));
  }
  index.message_index_length = position_ - indexes_start;
  chunks_.push_back(index);
  chunk_.clear();
  chunk_messages_.clear();
  std::fill(schema_in_chunk_.begin(), schema_in_chunk_.end(), false);
  std::fill(channel_in_chunk_.begin(), channel_in_chunk_.end(), false);
}

void McapWriter::close() {
  if (closed_) return;
  flushChunk();
  WriteFields data_end;
  data_end.number(data_crc_);
  data_ended_ = true;
  put(mcapRecord(kDataEnd, data_end.bytes()));

  // The summary: one group per record kind, each found by its Summary Offset.
  const std::uint64_t summary_start = position_;
  std::uint32_t summary_crc = 0;
  struct Group {
    Opcode opcode;
    std::uint64_t start, length;
  };
  std::vector<Group> groups;
  auto putGroup = [&](Opcode opcode, const std::vector<std::string>& records) {
    if (records.empty()) return;
    Group group{opcode, position_, 0};
    for (const std::string& r : records) {
      summary_crc = crc32(r, summary_crc);
      put(r);
    }
    group.length = position_ - group.start;
    groups.push_back(group);
  };
  std::vector<std::string> records;
  for (std::size_t i = 0; i < schemas_.size(); ++i) {
    records.push_back(schemaRecord(std::uint16_t(i + 1), schemas_[i].name, schemas_[i].encoding,
                                   schemas_[i].data));
  }
  putGroup(kSchema, records);
  records.clear();
  for (std::size_t i = 0; i < channels_.size(); ++i) {
    const Channel& c = channels_[i];
    records.push_back(
        channelRecord(std::uint16_t(i), c.schema, c.topic, c.message_encoding, c.metadata));
  }
  putGroup(kChannel, records);
  WriteFields counts;
  for (std::size_t i = 0; i < channels_.size(); ++i) {
    counts.number(std::uint16_t(i)).number(counts_[i]);
  }
  WriteFields statistics;
  statistics.number(messages_)
      .number(std::uint16_t(schemas_.size()))
      .number(std::uint32_t(channels_.size()))
      .number(std::uint32_t(0))  // attachments
      .number(std::uint32_t(0))  // metadata
      .number(std::uint32_t(chunks_.size()))
      .number(message_start_)
      .number(message_end_)
      .string(counts.bytes());
  putGroup(kStatistics, {mcapRecord(kStatistics, statistics.bytes())});
  records.clear();
  for (const ChunkIndex& c : chunks_) {
    WriteFields offsets;
    for (const auto& [channel, offset] : c.message_index_offsets) {
      offsets.number(channel).number(offset);
    }
    WriteFields f;
    f.number(c.start)
        .number(c.end)
        .number(c.offset)
        .number(c.length)
        .string(offsets.bytes())
        .number(c.message_index_length)
        .string(chunkCompression())
        .number(c.compressed_size)
        .number(c.uncompressed_size);
    records.push_back(mcapRecord(kChunkIndex, f.bytes()));
  }
  putGroup(kChunkIndex, records);
  const std::uint64_t summary_offset_start = position_;
  for (const Group& g : groups) {
    WriteFields f;
    f.number(std::uint8_t(g.opcode)).number(g.start).number(g.length);
    const std::string r = mcapRecord(kSummaryOffset, f.bytes());
    summary_crc = crc32(r, summary_crc);
    put(r);
  }
  // The footer's CRC covers the summary through the footer's own two offsets.
  WriteFields footer_prefix;
  footer_prefix.number(std::uint8_t(kFooter))
      .number(std::uint64_t(8 + 8 + 4))
      .number(summary_start)
      .number(summary_offset_start);
  summary_crc = crc32(footer_prefix.bytes(), summary_crc);
  WriteFields footer_crc;
  footer_crc.number(summary_crc);
  put(footer_prefix.bytes() + footer_crc.bytes());
  put(kMagic);
  out_.close();
  if (!out_) throw writeFailure(file_.path().string());
  file_.commit();
  closed_ = true;
}

void McapWriter::put(const std::string& bytes) {
  out_.write(bytes.data(), std::streamsize(bytes.size()));
  if (!out_) {
    throw common::InputError(file_.path().string(), "",
                             std::string("cannot write: ") + std::strerror(errno));
  }
  // Everything before Data End is the data section its CRC covers (the magic and Header too).
  if (!data_ended_) data_crc_ = crc32(bytes, data_crc_);
  position_ += bytes.size();
}

}  // namespace isg::formats
