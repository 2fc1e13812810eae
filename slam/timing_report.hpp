#pragma once

#include <string>
#include <vector>

#include "slam/map_diagnostics.hpp"

namespace isg::slam {

// Median and 95th percentile of the per-keyframe times around given graph sizes (keyframes
// [n - half_width, n + half_width)), to show whether the cost stays bounded as the graph grows.
// A hundred keyframes by default: what a window holds varies from place to place (a room with
// many walls, a revisit), and over twenty samples the p95 is just the largest of them.
struct TimingAt {
  int keyframes = 0;
  int samples = 0;
  double extraction_median_ms = 0, extraction_p95_ms = 0;  // the front end
  double planes_median_ms = 0, planes_p95_ms = 0;          // plane extraction alone
  double optimisation_median_ms = 0, optimisation_p95_ms = 0;
};
std::vector<TimingAt> timingAt(const std::vector<KeyframeTiming>& timings,
                               const std::vector<int>& sizes, int half_width = 50);
std::string formatTiming(const std::vector<TimingAt>& rows);

}  // namespace isg::slam
