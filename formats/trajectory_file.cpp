#include "formats/trajectory_file.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>

#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "common/tum.hpp"

namespace isg::formats {

common::Trajectory readTrajectoryFile(const std::string& path, bool require_poses) {
  common::Trajectory trajectory;
  try {
    trajectory = common::readTum(path);
  } catch (const common::TumError& e) {
    throw common::InputError(path, "", e.located());
  }
  if (require_poses && trajectory.empty()) {
    throw common::InputError(path, "", "no poses (a TUM file holds one pose per line)");
  }
  return trajectory;
}

std::vector<double> readStampsFile(const std::string& path) {
  common::checkRegularFile(path);
  std::ifstream in(path);
  if (!in) throw common::InputError(path, "", "cannot be read (no such file, or no permission)");
  std::vector<double> stamps;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    const auto last = line.find_last_not_of(" \t\r");
    const std::string text = line.substr(first, last - first + 1);
    char* end = nullptr;
    errno = 0;
    const double t = std::strtod(text.c_str(), &end);
    const auto where = "line " + std::to_string(number) + ": ";
    if (end != text.c_str() + text.size() || errno != 0 || !std::isfinite(t)) {
      throw common::InputError(path, "",
                               where + "expected one time in seconds, got \"" + text + "\"");
    }
    if (!stamps.empty() && !(t > stamps.back())) {
      throw common::InputError(path, "", where + "the time does not increase");
    }
    stamps.push_back(t);
  }
  return stamps;
}

}  // namespace isg::formats
