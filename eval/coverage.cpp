#include "eval/coverage.hpp"

#include <algorithm>

namespace isg::eval {

Coverage localizationCoverage(common::PoseSequence ground_truth, common::PoseSequence estimate,
                              double max_gap) {
  Coverage out;
  if (ground_truth.empty() || estimate.empty()) return out;
  double start = ground_truth.time(0), end = ground_truth.time(0);
  for (std::size_t i = 1; i < ground_truth.size(); ++i) {
    start = std::min(start, ground_truth.time(i));
    end = std::max(end, ground_truth.time(i));
  }
  // Only the estimate's rows within the ground truth's span say anything; rows before it mean
  // the method was localized when the ground truth began (time 0, never a negative time).
  std::vector<double> stamps;
  stamps.reserve(estimate.size() + 1);
  bool before = false;
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    const double t = estimate.time(i);
    if (t < start) {
      before = true;
    } else if (t <= end) {
      stamps.push_back(t);
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
