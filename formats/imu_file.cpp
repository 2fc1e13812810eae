#include "formats/imu_file.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "common/input_error.hpp"
#include "common/json_reader.hpp"

namespace isg::formats {

namespace {

constexpr const char* kHeader = "t,ax,ay,az,gx,gy,gz";
// As for TUM files: 1 GiB is ~8 M samples (11 hours at 200 Hz), read whole into memory.
constexpr std::uintmax_t kMaxImuBytes = std::uintmax_t(1) << 30;

// The seven numbers of one line, or false.
bool parseLine(const std::string& line, double (&values)[7]) {
  const char* at = line.c_str();
  for (int i = 0; i < 7; ++i) {
    char* end = nullptr;
    errno = 0;
    values[i] = std::strtod(at, &end);
    if (end == at || errno == ERANGE || !std::isfinite(values[i])) return false;
    at = end;
    if (i < 6) {
      if (*at != ',') return false;
      ++at;
    }
  }
  while (*at == ' ' || *at == '\r') ++at;
  return at == line.c_str() + line.size();  // the whole line: no byte after a NUL either
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
    if (!parseLine(line, v)) {
      throw common::InputError(
          path, "",
          "line " + std::to_string(number) + ": expected 7 comma-separated numbers: " + kHeader);
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
