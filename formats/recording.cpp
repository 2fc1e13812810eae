#include "formats/recording.hpp"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "common/input_error.hpp"
#include "formats/mcap_reader.hpp"
#include "formats/ros2_bag.hpp"
#include "formats/rosbag_reader.hpp"

namespace isg::formats {

namespace fs = std::filesystem;

namespace {

std::string lowerExtension(const fs::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

MessageEncoding encodingNamed(const std::string& name) {
  if (name == "cdr") return MessageEncoding::kCdr;
  if (name == "ros1") return MessageEncoding::kRos1;
  return MessageEncoding::kOther;
}

class Ros1Bag final : public Recording {
 public:
  explicit Ros1Bag(const std::string& path) : Recording(path, "ROS 1 bag"), bag_(path) {
    for (const auto& c : bag_.connections()) {
      topics_.push_back({c.topic, c.type.datatype, c.type.datatype, c.type.md5sum,
                         MessageEncoding::kRos1, "ros1", c.messages});
    }
    start_ = bag_.startTime();
  }
  void read(const std::vector<std::string>& topics,
            const std::function<bool(const RecordedMessage&)>& visit) override {
    bag_.read(topics, [&](const BagMessageView& m) {
      RecordedMessage message;
      message.topic = &topics_[std::size_t(m.connection - bag_.connections().data())];
      message.time = m.time;
      message.data = m.data;
      return visit(message);
    });
  }

 private:
  RosbagReader bag_;
};

// rosbag2's sqlite3 storage: a folder or one .db3.
class Ros2SqliteBag final : public Recording {
 public:
  explicit Ros2SqliteBag(const std::string& path)
      : Recording(path, "rosbag2 (sqlite3)"), bag_(path) {
    for (const auto& t : bag_.topics()) {
      topics_.push_back({t.name, ros1TypeName(t.type), t.type, "",
                         encodingNamed(t.serialization_format), t.serialization_format,
                         t.messages});
    }
    start_ = stampOf(bag_.startNs(), nullptr, -1);
  }
  void read(const std::vector<std::string>& topics,
            const std::function<bool(const RecordedMessage&)>& visit) override {
    bag_.read(topics, [&](const Ros2MessageView& m) {
      RecordedMessage message;
      message.topic = &topics_[std::size_t(m.topic - bag_.topics().data())];
      message.time = stampOf(m.stamp_ns, m.file, m.row);
      message.data = m.data;
      message.file = bag_.files().size() > 1 ? m.file : nullptr;
      message.row = m.row;
      return visit(message);
    });
  }

 private:
  RosTime stampOf(std::int64_t ns, const std::string* file, std::int64_t row) const {
    try {
      return rosTimeOfNanoseconds(ns);
    } catch (const std::invalid_argument& e) {
      throw common::InputError(file ? *file : path(), "",
                               (row >= 0 ? "row " + std::to_string(row) + ": " : std::string()) +
                                   "its timestamp " + std::to_string(ns) + " ns " + e.what());
    }
  }
  Ros2Bag bag_;
};

// One MCAP file, or the files of rosbag2's MCAP storage in their order (a split bag, each file's
// messages after the one before's).
class McapFiles final : public Recording {
 public:
  McapFiles(const std::string& path, const std::vector<std::string>& files, std::string kind)
      : Recording(path, std::move(kind)) {
    for (const auto& file : files) {
      auto reader = std::make_unique<McapReader>(file);
      if (!readers_.empty() && reader->messageCount() > 0 && readers_.back()->messageCount() > 0 &&
          reader->firstLogTime() < readers_.back()->lastLogTime()) {
        throw common::InputError(file, "",
                                 "its messages begin before the previous file's (" +
                                     fs::path(readers_.back()->name()).filename().string() +
                                     ") end: the files of a split bag follow one another");
      }
      offsets_.push_back(topics_.size());
      for (const auto& c : reader->channels()) {
        const bool ros2 = c.schema_encoding.rfind("ros2", 0) == 0 || c.message_encoding == "cdr";
        std::string md5;
        if (c.message_encoding == "ros1") {
          const auto it = c.metadata.find("md5sum");
          md5 = it == c.metadata.end() ? "" : it->second;
        }
        // A channel without a schema (JSON, say) is named by its encoding.
        const std::string type =
            c.schema_name.empty() ? c.message_encoding + " without a schema" : c.schema_name;
        topics_.push_back({c.topic, ros2 ? ros1TypeName(type) : type, type, md5,
                           encodingNamed(c.message_encoding), c.message_encoding, c.messages});
      }
      readers_.push_back(std::move(reader));
    }
    for (const auto& reader : readers_) {
      if (reader->messageCount() == 0) continue;
      start_ = stampOf(reader->firstLogTime(), *reader, 0, 0);
      break;
    }
  }
  void read(const std::vector<std::string>& topics,
            const std::function<bool(const RecordedMessage&)>& visit) override {
    for (std::size_t f = 0; f < readers_.size(); ++f) {
      McapReader& reader = *readers_[f];
      const auto has = [&](const std::string& topic) {
        return std::any_of(reader.channels().begin(), reader.channels().end(),
                           [&](const McapChannel& c) { return c.topic == topic; });
      };
      std::vector<std::string> here;
      for (const auto& topic : topics) {
        if (has(topic)) here.push_back(topic);
      }
      if (!topics.empty() && here.empty()) continue;
      bool more = true;
      reader.read(here, [&](const McapMessageView& m) {
        RecordedMessage message;
        message.topic = &topics_[offsets_[f] + std::size_t(m.channel - reader.channels().data())];
        message.time = stampOf(m.log_time_ns, reader, m.record_offset, m.chunk_offset);
        message.data = m.data;
        message.file = readers_.size() > 1 ? &reader.name() : nullptr;
        message.byte = m.record_offset;
        message.chunk_byte = m.chunk_offset;
        more = visit(message);
        return more;
      });
      if (!more) return;
    }
  }

 private:
  static RosTime stampOf(std::uint64_t ns, const McapReader& reader, std::uint64_t byte,
                         std::uint64_t chunk) {
    try {
      if (ns > std::uint64_t(INT64_MAX)) throw std::invalid_argument("is past 2106");
      return rosTimeOfNanoseconds(std::int64_t(ns));
    } catch (const std::invalid_argument& e) {
      RecordedMessage where;
      where.byte = byte;
      where.chunk_byte = chunk;
      throw common::InputError(
          reader.name(), "",
          placeOf(where) + ": its log time " + std::to_string(ns) + " ns " + e.what());
    }
  }
  std::vector<std::unique_ptr<McapReader>> readers_;
  std::vector<std::size_t> offsets_;  // each file's first topic in topics_
};

}  // namespace

std::string placeOf(const RecordedMessage& m) {
  std::string place;
  if (m.row >= 0) {
    place = "row " + std::to_string(m.row);
  } else if (m.chunk_byte != 0) {
    place =
        "byte " + std::to_string(m.byte) + " of the chunk at byte " + std::to_string(m.chunk_byte);
  } else if (m.byte != 0) {
    place = "the record at byte " + std::to_string(m.byte);
  }
  if (m.file && !place.empty()) place += " of " + fs::path(*m.file).filename().string();
  return place;
}

std::string ros1TypeName(const std::string& type) {
  const std::size_t at = type.find("/msg/");
  if (at == std::string::npos || type.find('/', at + 5) != std::string::npos) return type;
  return type.substr(0, at) + type.substr(at + 4);
}

RosTime rosTimeOfNanoseconds(std::int64_t ns) {
  if (ns < 0) throw std::invalid_argument("is before 1970");
  const std::uint64_t sec = std::uint64_t(ns) / 1000000000u;
  if (sec > 0xffffffffu) throw std::invalid_argument("is past 2106");
  return {std::uint32_t(sec), std::uint32_t(std::uint64_t(ns) % 1000000000u)};
}

bool isRecordingPath(const std::string& path) {
  const std::string extension = lowerExtension(path);
  if (extension == ".bag" || extension == ".db3" || extension == ".mcap") return true;
  std::error_code error;
  if (!fs::is_directory(path, error)) return false;
  if (fs::is_regular_file(fs::path(path) / "metadata.yaml", error)) return true;
  for (const auto& entry : fs::directory_iterator(path, error)) {
    if (lowerExtension(entry.path()) == ".db3") return true;
  }
  return false;
}

std::unique_ptr<Recording> openRecording(const std::string& path) {
  std::error_code error;
  if (!fs::exists(path, error)) throw common::InputError(path, "", "no such file or folder");
  const std::string extension = lowerExtension(path);
  if (fs::is_directory(path, error)) {
    const fs::path metadata = fs::path(path) / "metadata.yaml";
    if (fs::is_regular_file(metadata, error)) {
      const Rosbag2Storage storage = readRosbag2Metadata(metadata.string());
      if (storage.storage == "mcap") {
        return std::make_unique<McapFiles>(path, storage.files, "rosbag2 (mcap)");
      }
    }
    return std::make_unique<Ros2SqliteBag>(path);
  }
  if (extension == ".bag") return std::make_unique<Ros1Bag>(path);
  if (extension == ".db3") return std::make_unique<Ros2SqliteBag>(path);
  if (extension == ".mcap") return std::make_unique<McapFiles>(path, std::vector{path}, "MCAP");
  throw common::InputError(path, "",
                           "not a recording: a ROS 1 bag (.bag), a rosbag2 bag (its folder or a "
                           ".db3) or an MCAP file (.mcap) is read");
}

}  // namespace isg::formats
