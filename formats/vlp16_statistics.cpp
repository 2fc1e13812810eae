#include "formats/vlp16_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace isg::formats {

namespace {

// The q-quantile by the nearest rank of sorted values.
double quantile(const std::vector<std::uint8_t>& sorted, double q) {
  if (sorted.empty()) return 0.0;
  const auto rank = std::size_t(std::ceil(q * double(sorted.size())));
  return sorted[std::clamp<std::size_t>(rank, 1, sorted.size()) - 1];
}

}  // namespace

Vlp16Statistics vlp16Statistics(const Vlp16ShotTally& tally, const std::vector<Vlp16Turn>& turns) {
  Vlp16Statistics stats;
  std::uint64_t shots = 0, echoed = 0;
  for (int ring = 0; ring < 16; ++ring) {
    shots += tally.shots[ring];
    echoed += tally.echoed[ring];
    stats.lost_by_ring[ring] =
        tally.shots[ring] ? 1.0 - double(tally.echoed[ring]) / double(tally.shots[ring]) : 0.0;
  }
  stats.lost = shots ? 1.0 - double(echoed) / double(shots) : 0.0;
  std::vector<std::uint8_t> intensities;
  double points = 0.0, duration = 0.0;
  for (const auto& turn : turns) {
    for (const auto& p : turn.points) intensities.push_back(p.intensity);
    if (!turn.complete || turn.points.empty()) continue;
    ++stats.complete_turns;
    points += double(turn.points.size());
    const auto [earliest, latest] = std::minmax_element(
        turn.points.begin(), turn.points.end(),
        [](const Vlp16Point& a, const Vlp16Point& b) { return a.time < b.time; });
    duration += latest->time - earliest->time;
  }
  std::sort(intensities.begin(), intensities.end());
  stats.intensity_median = quantile(intensities, 0.5);
  stats.intensity_p99 = quantile(intensities, 0.99);
  stats.intensity_max = intensities.empty() ? 0.0 : intensities.back();
  if (stats.complete_turns > 0) {
    stats.points_per_turn = points / stats.complete_turns;
    stats.turn_duration = duration / stats.complete_turns;
  }
  return stats;
}

}  // namespace isg::formats
