#include "eval/coverage.hpp"

#include <algorithm>

namespace isg::eval {

Coverage localizationCoverage(const Trajectory& ground_truth, const Trajectory& estimate) {
  Coverage out;
  if (ground_truth.empty() || estimate.empty()) return out;
  const auto by_time = [](const StampedPose& a, const StampedPose& b) { return a.t < b.t; };
  const double start = std::min_element(ground_truth.begin(), ground_truth.end(), by_time)->t;
  const double end = std::max_element(ground_truth.begin(), ground_truth.end(), by_time)->t;
  const double first = std::min_element(estimate.begin(), estimate.end(), by_time)->t;
  out.localized = true;
  out.time_to_first = first - start;
  out.share = end > start ? std::clamp((end - first) / (end - start), 0.0, 1.0) : 1.0;
  return out;
}

}  // namespace isg::eval
