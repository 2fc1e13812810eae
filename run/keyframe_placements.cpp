#include "run/keyframe_placements.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace isg::run {

std::vector<std::optional<Eigen::Isometry3d>> keyframePlacements(const RunRecord& run) {
  std::vector<std::optional<Eigen::Isometry3d>> placements;
  if (!run.map) return placements;
  for (const auto& kf : run.map->keyframes) {
    const auto row = std::lower_bound(run.estimate.begin(), run.estimate.end(), kf.stamp - 1e-3,
                                      [](const StampedPose& pose, double t) { return pose.t < t; });
    const bool same_scan = row != run.estimate.end() && std::abs(row->t - kf.stamp) <= 1e-3;
    placements.push_back(same_scan ? std::optional(row->pose * kf.estimate.inverse())
                                   : std::nullopt);
  }
  // A segment that ended is one map, as the current one is: where the robot was not localized in
  // it, the placement of its keyframe nearest in time that was places it.
  const auto& keyframes = run.map->keyframes;
  const std::vector<std::optional<Eigen::Isometry3d>> own = placements;
  for (std::size_t i = 0; i < run.map->current_segment && i < keyframes.size(); ++i) {
    if (own[i]) continue;
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < run.map->current_segment && j < keyframes.size(); ++j) {
      const double apart = std::abs(keyframes[j].stamp - keyframes[i].stamp);
      if (own[j] && keyframes[j].segment == keyframes[i].segment && apart < nearest) {
        nearest = apart;
        placements[i] = own[j];
      }
    }
  }
  return placements;
}

std::optional<Eigen::Isometry3d> placementOfKeyframe(
    const RunRecord& run, const std::vector<std::optional<Eigen::Isometry3d>>& placements,
    std::size_t index) {
  if (!run.map || index >= run.map->current_segment) return run.final_B_T_M;
  return index < placements.size() ? placements[index] : std::nullopt;
}

}  // namespace isg::run
