#include "formats/imu_file.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>

#include "common/input_error.hpp"
#include "common/json_reader.hpp"

namespace isg::formats {

namespace {

constexpr const char* kHeader = "t,ax,ay,az,gx,gy,gz";
// As for TUM files: 1 GiB is ~8 M samples (11 hours at 200 Hz), read whole into memory.
constexpr std::uintmax_t kMaxImuBytes = std::uintmax_t(1) << 30;

// The seven numbers of one line; what is wrong with it otherwise, naming the column.
std::optional<std::string> parseLine(const std::string& line, double (&values)[7]) {
  static constexpr const char* kColumns[] = {"t", "ax", "ay", "az", "gx", "gy", "gz"};
  const char* at = line.c_str();
  for (int i = 0; i < 7; ++i) {
    const std::string column = "column " + std::to_string(i + 1) + " (" + kColumns[i] + "): ";
    char* end = nullptr;
    errno = 0;
    values[i] = std::strtod(at, &end);
    const std::string text(at, std::size_t(end - at));
    if (end == at) {
      if (*at == '\0') {
        return "expected 7 comma-separated numbers (" + std::string(kHeader) + "), got " +
               std::to_string(i);
      }
      return column + "not a number";
    }
    if (std::isnan(values[i])) return column + "\"" + text + "\" is not a number";
    if (errno == ERANGE || !std::isfinite(values[i])) {
      return column + "\"" + text + "\" is out of range (not a finite double)";
    }
    at = end;
    if (i < 6) {
      if (*at != ',') {
        return *at == '\0' ? "expected 7 comma-separated numbers (" + std::string(kHeader) +
                                 "), got " + std::to_string(i + 1)
                           : column + "expected a comma after the number";
      }
      ++at;
    }
  }
  while (*at == ' ' || *at == '\r') ++at;
  // The whole line: no byte after a NUL either.
  if (at != line.c_str() + line.size()) return std::string("text after the 7th number");
  return std::nullopt;
}

}  // namespace

std::vector<sensors::ImuSample> readImuFile(const std::string& path) {
  return parseImuText(common::readCheckedFile(path, kMaxImuBytes), path);
}

std::vector<sensors::ImuSample> parseImuText(std::string_view text, const std::string& path) {
  std::istringstream in{std::string(text)};
  std::string line;
  if (!std::getline(in, line) || (line != kHeader && line != std::string(kHeader) + "\r")) {
    throw common::InputError(path, "",
                             std::string("line 1: expected the header \"") + kHeader + "\"");
  }
  std::vector<sensors::ImuSample> samples;
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    double v[7];
    if (const auto wrong = parseLine(line, v)) {
      throw common::InputError(path, "", "line " + std::to_string(number) + ": " + *wrong);
    }
    if (!samples.empty() && !(v[0] > samples.back().t)) {
      throw common::InputError(path, "",
                               "line " + std::to_string(number) + ": time does not increase");
    }
    sensors::ImuSample s;
    s.t = v[0];
    s.accelerometer = Eigen::Vector3d(v[1], v[2], v[3]);
    s.gyroscope = Eigen::Vector3d(v[4], v[5], v[6]);
    samples.push_back(s);
  }
  return samples;
}

}  // namespace isg::formats
