#include "eval/floor_plan_score.hpp"

#include <cmath>

#include <optional>

namespace isg::eval {

FloorPlanScore floorPlanScore(common::PoseSequence reference, common::PoseSequence estimate,
                              const FloorPlanScoreOptions& options) {
  FloorPlanScore out;
  if (reference.empty()) return out;
  const double from = reference[0].t + options.skip;
  double sum = 0.0;
  int estimated = 0;
  std::size_t next = 0;  // the first estimate row at or after the reference pose (both in order)
  for (std::size_t i = 0; i < reference.size(); ++i) {
    const common::StampedPose g = reference[i];
    if (g.t < from) continue;
    ++out.poses;
    while (next < estimate.size() && estimate[next].t < g.t - 1e-3) ++next;
    std::optional<Eigen::Vector2d> at;
    if (next < estimate.size() && std::abs(estimate[next].t - g.t) <= 1e-3) {
      at = estimate[next].pose.translation().head<2>();
    } else if (next > 0 && next < estimate.size()) {
      const common::StampedPose a = estimate[next - 1], b = estimate[next];
      if (b.t - a.t <= options.max_gap) {
        const double w = (g.t - a.t) / (b.t - a.t);
        at = (1.0 - w) * a.pose.translation().head<2>() + w * b.pose.translation().head<2>();
      }
    }
    if (!at) continue;
    ++estimated;
    sum += 100.0 * std::exp(-options.decay * (*at - g.pose.translation().head<2>()).norm());
  }
  if (out.poses == 0) return out;
  out.coverage = double(estimated) / double(out.poses);
  out.score = out.coverage >= options.min_coverage ? sum / double(out.poses) : 0.0;
  return out;
}

}  // namespace isg::eval
