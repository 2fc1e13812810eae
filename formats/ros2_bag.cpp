#include "formats/ros2_bag.hpp"

#include <sqlite3.h>

#include <algorithm>
#include <filesystem>
#include <memory>

#include "common/input_error.hpp"

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

// Runs `sql` (with ?1 bound to `parameter` when given) on one database file and calls
// row(statement) for each row.
template <class Row>
void query(const std::string& file, const char* sql, const std::string* parameter, Row&& row) {
  const Database db = open(file);
  const Statement statement = prepare(db.get(), file, sql);
  if (parameter) sqlite3_bind_text(statement.get(), 1, parameter->c_str(), -1, SQLITE_TRANSIENT);
  int status;
  while ((status = sqlite3_step(statement.get())) == SQLITE_ROW) row(statement.get());
  if (status != SQLITE_DONE) {
    throw common::InputError(file, "", std::string("reading the bag: ") + sqlite3_errmsg(db.get()));
  }
}

std::string textColumn(sqlite3_stmt* statement, int column) {
  const auto* text = sqlite3_column_text(statement, column);
  return text ? reinterpret_cast<const char*>(text) : "";
}

}  // namespace

Ros2Bag::Ros2Bag(const std::string& path) : path_(path) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (fs::is_directory(path, error)) {
    for (const auto& entry : fs::directory_iterator(path, error)) {
      if (entry.path().extension() == ".db3") files_.push_back(entry.path().string());
    }
    std::sort(files_.begin(), files_.end());
    if (files_.empty()) {
      throw common::InputError(path, "", "a folder without .db3 files, not a ROS 2 bag");
    }
  } else if (fs::is_regular_file(path, error)) {
    files_.push_back(path);
  } else {
    throw common::InputError(path, "", "no such file or folder");
  }
  for (const auto& file : files_) {
    query(file,
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
  }
}

std::vector<Ros2Message> Ros2Bag::messages(const std::string& topic) const {
  const bool known = std::any_of(topics_.begin(), topics_.end(),
                                 [&](const Ros2Topic& t) { return t.name == topic; });
  if (!known) {
    std::string names;
    for (const auto& t : topics_) names += (names.empty() ? "" : ", ") + t.name;
    throw common::InputError(
        path_, "",
        "no topic " + topic + " (the bag has: " + (names.empty() ? "no topics" : names) + ")");
  }
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
