#include "sim/scan_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <utility>

#include "sim/vlp16.hpp"

namespace isg::sim {

formats::Vlp16Statistics scanStatistics(const std::vector<LidarScan>& clouds,
                                        int sequences_per_cloud) {
  formats::Vlp16ShotTally tally;
  std::vector<formats::Vlp16Turn> turns;
  for (const LidarScan& cloud : clouds) {
    for (int ring = 0; ring < Vlp16::kLasers; ++ring) tally.shots[ring] += sequences_per_cloud;
    // A shot is its ring and instant: dual returns give one shot two points.
    std::set<std::pair<int, float>> echoed;
    formats::Vlp16Turn turn;
    turn.complete = true;
    turn.points.reserve(cloud.points.size());
    for (const LidarPoint& p : cloud.points) {
      if (echoed.emplace(p.ring, p.time).second) ++tally.echoed[p.ring];
      formats::Vlp16Point point;
      point.x = p.x;
      point.y = p.y;
      point.z = p.z;
      const int laser = Vlp16::laser(p.ring);
      point.distance = float((Eigen::Vector3d(p.x, p.y, p.z) - Vlp16::origin(laser)).norm());
      const double clockwise = -std::atan2(double(p.y), double(p.x)) * 180.0 / std::numbers::pi;
      point.azimuth = std::uint16_t(std::lround(std::fmod(clockwise + 360.0, 360.0) * 100) % 36000);
      point.intensity = std::uint8_t(std::min(255.0f, std::max(0.0f, p.intensity)));
      point.laser = std::uint8_t(laser);
      point.ring = std::uint8_t(p.ring);
      point.time = cloud.stamp + p.time;
      turn.points.push_back(point);
    }
    turns.push_back(std::move(turn));
  }
  return formats::vlp16Statistics(tally, turns);
}

}  // namespace isg::sim
