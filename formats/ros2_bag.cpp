#include "formats/ros2_bag.hpp"

#include <sqlite3.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <utility>

#include "common/input_error.hpp"
#include "common/json_reader.hpp"

namespace isg::formats {

namespace {

struct DatabaseCloser {
  void operator()(sqlite3* db) const { sqlite3_close(db); }
};
struct StatementFinalizer {
  void operator()(sqlite3_stmt* statement) const { sqlite3_finalize(statement); }
};
using Database = std::unique_ptr<sqlite3, DatabaseCloser>;
using Statement = std::unique_ptr<sqlite3_stmt, StatementFinalizer>;

Database open(const std::string& file) {
  common::checkRegularFile(file);
  sqlite3* raw = nullptr;
  const int status = sqlite3_open_v2(file.c_str(), &raw, SQLITE_OPEN_READONLY, nullptr);
  Database db(raw);
  if (status != SQLITE_OK) {
    throw common::InputError(file, "",
                             std::string("cannot open as SQLite: ") +
                                 (raw ? sqlite3_errmsg(raw) : sqlite3_errstr(status)));
  }
  return db;
}

Statement prepare(sqlite3* db, const std::string& file, const char* sql) {
  sqlite3_stmt* raw = nullptr;
  if (sqlite3_prepare_v2(db, sql, -1, &raw, nullptr) != SQLITE_OK) {
    throw common::InputError(file, "",
                             std::string("not a ROS 2 bag database (") + sqlite3_errmsg(db) + ")");
  }
  return Statement(raw);
}

// Runs `sql` (with ?1 bound to `parameter` when given) on the open database of `file` and calls
// row(statement) for each row.
template <class Row>
void query(sqlite3* db, const std::string& file, const char* sql, const std::string* parameter,
           Row&& row) {
  const Statement statement = prepare(db, file, sql);
  if (parameter) sqlite3_bind_text(statement.get(), 1, parameter->c_str(), -1, SQLITE_TRANSIENT);
  int status;
  while ((status = sqlite3_step(statement.get())) == SQLITE_ROW) row(statement.get());
  if (status != SQLITE_DONE) {
    throw common::InputError(file, "", std::string("reading the bag: ") + sqlite3_errmsg(db));
  }
}

// The same on the database file `file`, opened for the query.
template <class Row>
void query(const std::string& file, const char* sql, const std::string* parameter, Row&& row) {
  const Database db = open(file);
  query(db.get(), file, sql, parameter, std::forward<Row>(row));
}

std::string textColumn(sqlite3_stmt* statement, int column) {
  const auto* text = sqlite3_column_text(statement, column);
  return text ? reinterpret_cast<const char*>(text) : "";
}

}  // namespace

Rosbag2Storage readRosbag2Metadata(const std::string& metadata_file) {
  namespace fs = std::filesystem;
  // A bag's metadata is a few kB: 16 MiB is far beyond any, and keeps yaml-cpp's tree small.
  const std::string text_of_file = common::readCheckedFile(metadata_file, 16u << 20);
  YAML::Node root;
  try {
    root = YAML::Load(text_of_file);
  } catch (const YAML::Exception& e) {
    throw common::InputError(metadata_file, "", std::string("not YAML: ") + e.what());
  }
  const YAML::Node info = root.IsMap() ? root["rosbag2_bagfile_information"] : YAML::Node();
  if (!info || !info.IsMap()) {
    throw common::InputError(metadata_file, "",
                             "no rosbag2_bagfile_information: not a rosbag2 bag's metadata");
  }
  const auto text = [&](const char* key) -> std::string {
    const YAML::Node node = info[key];
    if (!node) return "";
    if (!node.IsScalar()) {
      throw common::InputError(
          metadata_file, "",
          std::string("rosbag2_bagfile_information.") + key + " is not a single value");
    }
    return node.as<std::string>();
  };
  Rosbag2Storage out;
  out.storage = text("storage_identifier");
  if (out.storage.empty()) out.storage = "sqlite3";  // the only storage before Humble
  if (out.storage != "sqlite3" && out.storage != "mcap") {
    throw common::InputError(metadata_file, "",
                             "unknown storage \"" + out.storage +
                                 "\" (rosbag2 writes \"sqlite3\" or "
                                 "\"mcap\")");
  }
  const std::string compression_mode = text("compression_mode");
  if (!compression_mode.empty()) {
    throw common::InputError(metadata_file, "",
                             "a compressed bag (compression_mode " + compression_mode +
                                 ", format " + text("compression_format") +
                                 ") is not read; write it uncompressed (ros2 bag convert)");
  }
  const YAML::Node paths = info["relative_file_paths"];
  if (!paths || !paths.IsSequence() || paths.size() == 0) {
    throw common::InputError(metadata_file, "",
                             "rosbag2_bagfile_information.relative_file_paths lists no file");
  }
  const fs::path folder = fs::path(metadata_file).parent_path();
  for (std::size_t k = 0; k < paths.size(); ++k) {
    if (!paths[k].IsScalar()) {
      throw common::InputError(metadata_file, "",
                               "relative_file_paths[" + std::to_string(k) + "] is not a file name");
    }
    const fs::path file = folder / paths[k].as<std::string>();
    std::error_code error;
    if (!fs::is_regular_file(file, error)) {
      throw common::InputError(metadata_file, "",
                               "relative_file_paths[" + std::to_string(k) + "] names " +
                                   file.filename().string() + ", which is not in the folder");
    }
    out.files.push_back(file.string());
  }
  return out;
}

Ros2Bag::Ros2Bag(const std::string& path) : path_(path) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::path metadata = fs::path(path) / "metadata.yaml";
  if (fs::is_directory(path, error) && fs::is_regular_file(metadata, error)) {
    Rosbag2Storage storage = readRosbag2Metadata(metadata.string());
    if (storage.storage != "sqlite3") {
      throw common::InputError(metadata.string(), "",
                               "storage \"" + storage.storage +
                                   "\": not the sqlite3 storage (.db3) this reader reads; read "
                                   "its files as MCAP");
    }
    files_ = std::move(storage.files);
  } else if (fs::is_directory(path, error)) {
    for (const auto& entry : fs::directory_iterator(path, error)) {
      if (entry.path().extension() == ".db3") files_.push_back(entry.path().string());
    }
    std::sort(files_.begin(), files_.end());
    if (files_.empty()) {
      throw common::InputError(path, "", "a folder without .db3 files, not a ROS 2 bag");
    }
  } else if (fs::exists(path, error)) {
    files_.push_back(path);  // a file: open() refuses anything but a regular one, unopened
  } else {
    throw common::InputError(path, "", "no such file or folder");
  }
  for (const auto& file : files_) {
    const Database db = open(file);  // both queries on one connection
    query(db.get(), file,
          "SELECT t.name, t.type, t.serialization_format, COUNT(m.id) FROM topics t "
          "LEFT JOIN messages m ON m.topic_id = t.id GROUP BY t.id ORDER BY t.name",
          nullptr, [this](sqlite3_stmt* row) {
            Ros2Topic topic{textColumn(row, 0), textColumn(row, 1), textColumn(row, 2),
                            std::size_t(sqlite3_column_int64(row, 3))};
            auto same = std::find_if(topics_.begin(), topics_.end(),
                                     [&](const Ros2Topic& t) { return t.name == topic.name; });
            if (same == topics_.end()) {
              topics_.push_back(topic);
            } else {
              same->messages += topic.messages;
            }
          });
    bool first = start_ns_ == 0;
    query(db.get(), file, "SELECT MIN(timestamp) FROM messages", nullptr, [&](sqlite3_stmt* row) {
      if (sqlite3_column_type(row, 0) == SQLITE_NULL) return;  // no message in this file
      const std::int64_t stamp = sqlite3_column_int64(row, 0);
      if (first || stamp < start_ns_) start_ns_ = stamp;
      first = false;
    });
  }
}

void Ros2Bag::expectTopic(const std::string& topic) const {
  const bool known = std::any_of(topics_.begin(), topics_.end(),
                                 [&](const Ros2Topic& t) { return t.name == topic; });
  if (!known) {
    std::string names;
    for (const auto& t : topics_) names += (names.empty() ? "" : ", ") + t.name;
    throw common::InputError(
        path_, "",
        "no topic " + topic + " (the bag has: " + (names.empty() ? "no topics" : names) + ")");
  }
}

void Ros2Bag::read(const std::vector<std::string>& topics,
                   const std::function<bool(const Ros2MessageView&)>& visit) const {
  for (const auto& topic : topics) expectTopic(topic);
  // One statement a file, each stepping through its rows of the topics asked for in stamp order
  // (the others are never read: a bag's camera images stay on disk); the next message is the
  // earliest of their current rows (a k-way merge: split bags' files may overlap in time).
  std::string sql =
      "SELECT m.timestamp, m.data, t.name, m.id FROM messages m JOIN topics t ON m.topic_id = t.id";
  for (std::size_t k = 0; k < topics.size(); ++k) {
    sql += (k == 0 ? " WHERE t.name IN (?" : ", ?") + std::to_string(k + 1);
  }
  sql += std::string(topics.empty() ? "" : ")") + " ORDER BY m.timestamp, m.id";
  struct Cursor {
    std::string file;
    Database db;
    Statement statement;
    bool row = false;
  };
  std::vector<Cursor> cursors;
  for (const auto& file : files_) {
    Cursor cursor{file, open(file), nullptr, false};
    cursor.statement = prepare(cursor.db.get(), file, sql.c_str());
    for (std::size_t k = 0; k < topics.size(); ++k) {
      sqlite3_bind_text(cursor.statement.get(), int(k + 1), topics[k].c_str(), -1,
                        SQLITE_TRANSIENT);
    }
    cursors.push_back(std::move(cursor));
  }
  const auto step = [](Cursor& c) {
    const int status = sqlite3_step(c.statement.get());
    c.row = status == SQLITE_ROW;
    if (!c.row && status != SQLITE_DONE) {
      throw common::InputError(c.file, "",
                               std::string("reading the bag: ") + sqlite3_errmsg(c.db.get()));
    }
  };
  for (Cursor& c : cursors) step(c);
  std::uint64_t index = 0;
  while (true) {
    Cursor* next = nullptr;
    for (Cursor& c : cursors) {
      if (c.row && (next == nullptr || sqlite3_column_int64(c.statement.get(), 0) <
                                           sqlite3_column_int64(next->statement.get(), 0))) {
        next = &c;
      }
    }
    if (next == nullptr) return;
    sqlite3_stmt* row = next->statement.get();
    const std::string name = textColumn(row, 2);
    Ros2MessageView view;
    view.topic = &*std::find_if(topics_.begin(), topics_.end(),
                                [&](const Ros2Topic& t) { return t.name == name; });
    view.stamp_ns = sqlite3_column_int64(row, 0);
    const auto* blob = static_cast<const char*>(sqlite3_column_blob(row, 1));
    view.data = std::string_view(blob ? blob : "", std::size_t(sqlite3_column_bytes(row, 1)));
    view.index = index++;
    view.file = &next->file;
    view.row = sqlite3_column_int64(row, 3);
    if (!visit(view)) return;
    step(*next);
  }
}

std::vector<Ros2Message> Ros2Bag::messages(const std::string& topic) const {
  expectTopic(topic);
  std::vector<Ros2Message> out;
  for (const auto& file : files_) {
    query(file,
          "SELECT m.timestamp, m.data FROM messages m JOIN topics t ON m.topic_id = t.id "
          "WHERE t.name = ?1 ORDER BY m.timestamp, m.id",
          &topic, [&out](sqlite3_stmt* row) {
            Ros2Message message;
            message.stamp_ns = sqlite3_column_int64(row, 0);
            const auto* blob = static_cast<const char*>(sqlite3_column_blob(row, 1));
            message.data.assign(blob ? blob : "", std::size_t(sqlite3_column_bytes(row, 1)));
            out.push_back(std::move(message));
          });
  }
  std::stable_sort(out.begin(), out.end(), [](const Ros2Message& a, const Ros2Message& b) {
    return a.stamp_ns < b.stamp_ns;
  });
  return out;
}

}  // namespace isg::formats
