#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "run/run_record.hpp"

namespace isg::run {

// Where the map lay in the plan as each of its keyframes was taken: the localizer's pose in B at
// the keyframe's scan composed with the keyframe's final pose in M (B_T_M then), one per
// run.map->keyframes; none where the pose at that scan was not confirmed by the plan (its state
// tracking or lost, run/estimate_states.hpp), nor where there was no pose in B. The final B_T_M
// (as the plan last confirmed it, LocalizerDriver::confirmedMapInPlan) places the current
// segment's map; a segment that ended (MapDiagnostics::current_segment) is
// placed only by these, since each segment merely continues M from where the last one ended: there,
// a keyframe taken while the robot was not localized (no pose in B, or lost) gets the placement of
// the one nearest in time of its segment that was (none when none was); one taken while tracking
// stays unplaced: the report judges nothing from it.
std::vector<std::optional<Eigen::Isometry3d>> keyframePlacements(const RunRecord& run);

// Where the keyframe `index` of run.map lies in B: by the final B_T_M in the current segment, by
// its own placement (keyframePlacements) in one that ended; none when there is none.
std::optional<Eigen::Isometry3d> placementOfKeyframe(
    const RunRecord& run, const std::vector<std::optional<Eigen::Isometry3d>>& placements,
    std::size_t index);

}  // namespace isg::run
