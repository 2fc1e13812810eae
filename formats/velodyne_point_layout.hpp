#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

#include "sensors/messages.hpp"

namespace isg::formats {

// The Velodyne ROS driver's PointCloud2 point, which both exported clouds use (ROS 1 bag, MCAP):
// x y z intensity (float32 at 0, 4, 8, 12), ring (uint16 at 16), time (float32 at 18, seconds
// from the stamp).
inline constexpr std::uint32_t kVelodynePointStep = 22;

// Writes `points` in that layout at `out` (kVelodynePointStep bytes each).
inline void packVelodynePoints(const std::vector<sensors::ScanPoint>& points, void* out) {
  auto* at = static_cast<unsigned char*>(out);
  for (const sensors::ScanPoint& p : points) {
    std::memcpy(at + 0, &p.x, 4);
    std::memcpy(at + 4, &p.y, 4);
    std::memcpy(at + 8, &p.z, 4);
    std::memcpy(at + 12, &p.intensity, 4);
    std::memcpy(at + 16, &p.ring, 2);
    std::memcpy(at + 18, &p.time, 4);
    at += kVelodynePointStep;
  }
}

}  // namespace isg::formats
