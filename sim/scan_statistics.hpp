#pragma once

#include <vector>

#include "formats/vlp16_statistics.hpp"
#include "sim/lidar_simulator.hpp"

namespace isg::sim {

// The return statistics of simulated clouds (docs/sensors.md), computed by the very code that
// measures a real recording: each cloud is one complete turn of `sequences_per_cloud` firing
// sequences, every (sequence, laser) a shot; a shot with any point has an echo. Points become
// decoded returns (distance from the laser's origin, azimuth clockwise from x in 0.01°).
formats::Vlp16Statistics scanStatistics(const std::vector<LidarScan>& clouds,
                                        int sequences_per_cloud);

}  // namespace isg::sim
