#include "run/keyframe_placements.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace isg::run {

std::vector<std::optional<Eigen::Isometry3d>> keyframePlacements(const RunRecord& run) {
  std::vector<std::optional<Eigen::Isometry3d>> placements;
  if (!run.map) return placements;
  std::vector<bool> tracked;  // placed while the plan did not confirm: never filled in below
  for (const auto& kf : run.map->keyframes) {
    const auto row = std::lower_bound(run.estimate.begin(), run.estimate.end(), kf.stamp - 1e-3,
                                      [](const StampedPose& pose, double t) { return pose.t < t; });
    const bool same_scan = row != run.estimate.end() && std::abs(row->t - kf.stamp) <= 1e-3;
    // Only what the plan confirmed places a keyframe: a pose carried by the map alone (tracking)
    // or by the last answer while lost would judge the building from a guess.
    const std::size_t index = std::size_t(row - run.estimate.begin());
    const bool stated = same_scan && index < run.estimate_states.size();
    const bool confirmed =
        same_scan && (!stated || run.estimate_states[index].state == PoseState::kLocalized);
    tracked.push_back(stated && run.estimate_states[index].state == PoseState::kTracking);
    placements.push_back(confirmed ? std::optional(row->pose * kf.estimate.inverse())
                                   : std::nullopt);
  }
  // A segment that ended is one map, as the current one is: where the robot was not localized in
  // it (no pose in B, or the last answer's while lost), the placement of its keyframe nearest in
  // time that was places it; a keyframe tracked without the plan's confirmation stays out. The
  // keyframes are in time order: the nearest is the last localized before or the first after, in
  // its segment.
  const auto& keyframes = run.map->keyframes;
  const std::size_t ended = std::min(run.map->current_segment, keyframes.size());
  std::vector<std::optional<std::size_t>> before(ended), after(ended);
  for (std::size_t i = 0; i < ended; ++i) {
    if (placements[i]) {
      before[i] = i;
    } else if (i > 0 && keyframes[i - 1].segment == keyframes[i].segment) {
      before[i] = before[i - 1];
    }
  }
  for (std::size_t i = ended; i-- > 0;) {
    if (placements[i]) {
      after[i] = i;
    } else if (i + 1 < ended && keyframes[i + 1].segment == keyframes[i].segment) {
      after[i] = after[i + 1];
    }
  }
  for (std::size_t i = 0; i < ended; ++i) {
    if (placements[i] || tracked[i]) continue;
    const auto apart = [&](const std::optional<std::size_t>& j) {
      return j ? std::abs(keyframes[*j].stamp - keyframes[i].stamp)
               : std::numeric_limits<double>::infinity();
    };
    const std::optional<std::size_t> nearest =
        apart(before[i]) <= apart(after[i]) ? before[i] : after[i];
    if (nearest) placements[i] = placements[*nearest];
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
