#include "eval/coverage.hpp"

#include <algorithm>

namespace isg::eval {

Coverage localizationCoverage(const common::Trajectory& ground_truth,
                              const common::Trajectory& estimate, double max_gap) {
  Coverage out;
  if (ground_truth.empty() || estimate.empty()) return out;
  const auto by_time = [](const common::StampedPose& a, const common::StampedPose& b) {
    return a.t < b.t;
  };
  const double start = std::min_element(ground_truth.begin(), ground_truth.end(), by_time)->t;
  const double end = std::max_element(ground_truth.begin(), ground_truth.end(), by_time)->t;
  // Only the estimate's rows within the ground truth's span say anything; rows before it mean
  // the method was localized when the ground truth began (time 0, never a negative time).
  std::vector<double> stamps;
  stamps.reserve(estimate.size() + 1);
  bool before = false;
  for (const auto& p : estimate) {
    if (p.t < start) {
      before = true;
    } else if (p.t <= end) {
      stamps.push_back(p.t);
    }
  }
  if (before) stamps.push_back(start);
  if (stamps.empty()) return out;
  std::sort(stamps.begin(), stamps.end());
  const double first = stamps.front();
  for (std::size_t i = 1; i < stamps.size(); ++i) {
    const double gap = stamps[i] - stamps[i - 1];
    if (gap > max_gap) out.lost_seconds += gap;
  }
  if (end - stamps.back() > max_gap) out.lost_seconds += end - stamps.back();
  out.localized = true;
  out.time_to_first = first - start;
  out.share =
      end > start ? std::clamp((end - first - out.lost_seconds) / (end - start), 0.0, 1.0) : 1.0;
  return out;
}

}  // namespace isg::eval
