#include "bim/recorded_start_pose.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <vector>

#include "common/decimal_number.hpp"
#include "common/input_error.hpp"
#include "common/tum.hpp"

namespace isg::bim {

namespace {

constexpr int kStartPoseFields = 10;  // sequence, plan, stamp, tx ty tz, qx qy qz qw

std::string_view trimmed(std::string_view text) {
  const std::size_t first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const std::size_t last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

std::vector<std::string_view> csvFields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t at = 0;
  while (true) {
    const std::size_t comma = line.find(',', at);
    fields.push_back(
        trimmed(line.substr(at, comma == std::string_view::npos ? line.npos : comma - at)));
    if (comma == std::string_view::npos) return fields;
    at = comma + 1;
  }
}

std::string fileText(const std::string& path) {
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (!std::filesystem::exists(status)) throw common::InputError(path, "", "cannot open file");
  if (!std::filesystem::is_regular_file(status)) {
    throw common::InputError(path, "", "not a regular file");
  }
  const auto bytes = std::filesystem::file_size(path, error);
  if (!error && bytes > kMaxStartPoseTableBytes) {
    throw common::InputError(path, "",
                             "file is " + std::to_string(bytes) + " bytes; a start pose table " +
                                 "holds one row a run (at most " +
                                 std::to_string(kMaxStartPoseTableBytes) + " bytes are read)");
  }
  std::ifstream in(path);
  if (!in) throw common::InputError(path, "", "cannot open file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The row's pose, or an InputError naming its line.
RecordedStartPose parseRow(const std::vector<std::string_view>& fields, const std::string& path,
                           int line) {
  const auto wrong = [&](const std::string& reason) {
    return common::InputError(path, "", "line " + std::to_string(line) + ": " + reason);
  };
  double v[8];
  static const char* const kNames[8] = {"timestamp", "tx", "ty", "tz", "qx", "qy", "qz", "qw"};
  for (int k = 0; k < 8; ++k) {
    const std::optional<double> value = common::parseDecimal(fields[2 + k]);
    if (!value) {
      throw wrong(std::string(kNames[k]) + " (\"" + std::string(fields[2 + k].substr(0, 40)) +
                  "\") is not a finite decimal number");
    }
    v[k] = *value;
  }
  if (std::abs(v[0]) > common::kMaxTumTime) throw wrong("the timestamp is out of range");
  for (int k = 1; k <= 3; ++k) {
    if (std::abs(v[k]) > common::kMaxTumCoordinate) {
      throw wrong(std::string(kNames[k]) + " is out of range (at most 1e9 m from the origin)");
    }
  }
  const Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
  if (std::abs(q.norm() - 1.0) > 1e-3) throw wrong("the quaternion is not of unit length");
  RecordedStartPose row;
  row.sequence = std::string(fields[0]);
  row.plan_file = std::string(fields[1]);
  row.stamp = v[0];
  row.pose.translation() = Eigen::Vector3d(v[1], v[2], v[3]);
  row.pose.linear() = q.normalized().toRotationMatrix();
  row.line = line;
  return row;
}

}  // namespace

RecordedStartPose readRecordedStartPose(const std::string& path, const std::string& sequence) {
  const std::string text = fileText(path);
  std::istringstream lines(text);
  std::string line;
  int number = 0;
  std::optional<RecordedStartPose> found;
  std::vector<std::string> sequences;
  while (std::getline(lines, line)) {
    ++number;
    const std::string_view content = trimmed(line);
    if (content.empty() || content.front() == '#') continue;
    const std::vector<std::string_view> fields = csvFields(content);
    if (int(fields.size()) != kStartPoseFields) {
      throw common::InputError(
          path, "",
          "line " + std::to_string(number) + ": expected " + std::to_string(kStartPoseFields) +
              " fields (sequence, floor plan, timestamp, tx, ty, tz, qx, qy, qz, qw), found " +
              std::to_string(fields.size()));
    }
    if (fields[0].empty()) {
      throw common::InputError(path, "", "line " + std::to_string(number) + ": no sequence name");
    }
    // Every row is checked, not only the one asked for: a damaged table is said at once.
    RecordedStartPose row = parseRow(fields, path, number);
    sequences.push_back(row.sequence);
    if (row.sequence != sequence) continue;
    if (found) {
      throw common::InputError(path, "",
                               "line " + std::to_string(number) + ": sequence \"" + sequence +
                                   "\" is given twice (first on line " +
                                   std::to_string(found->line) + ")");
    }
    found = std::move(row);
  }
  if (!found) {
    std::string known;
    for (std::size_t k = 0; k < sequences.size() && k < 12; ++k) {
      known += (k == 0 ? "" : ", ") + sequences[k];
    }
    if (sequences.size() > 12) known += ", …";
    throw common::InputError(path, "",
                             "no row for sequence \"" + sequence + "\"" +
                                 (sequences.empty() ? std::string(": the table has no rows")
                                                    : "; the table has " + known));
  }
  return *found;
}

}  // namespace isg::bim
