#pragma once

#include <cstdint>

namespace isg::formats {

// ROS 1 time: seconds and nanoseconds since the epoch, as ROS 1 bags, their messages, ROS 2's
// builtin_interfaces/Time and Foxglove's messages stamp them. Its own header: the run's MCAP
// writer and the Foxglove messages need the stamp, not the bag writer.
struct RosTime {
  std::uint32_t sec = 0;
  std::uint32_t nsec = 0;
  // `seconds` ≥ 0, rounded to the nanosecond, plus `offset` whole seconds (added as an integer:
  // a double near 1e9 s holds time only to ~0.1 µs).
  static RosTime fromSeconds(double seconds, std::uint32_t offset = 0);
  bool operator<(const RosTime& o) const { return sec != o.sec ? sec < o.sec : nsec < o.nsec; }
};

}  // namespace isg::formats
