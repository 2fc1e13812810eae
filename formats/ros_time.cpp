#include "formats/ros_time.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace isg::formats {

RosTime RosTime::fromSeconds(double seconds, std::uint32_t offset) {
  const double limit = 4294967296.0 - double(offset);
  if (!(seconds >= 0.0) || seconds >= limit) {
    throw std::invalid_argument("ROS time out of range: " + std::to_string(seconds) + " s + " +
                                std::to_string(offset) + " s");
  }
  const auto total = std::uint64_t(std::llround(seconds * 1e9));
  const std::uint64_t sec = total / 1000000000u + offset;
  if (sec > 0xffffffffu) throw std::invalid_argument("ROS time out of range");
  return {std::uint32_t(sec), std::uint32_t(total % 1000000000u)};
}

}  // namespace isg::formats
