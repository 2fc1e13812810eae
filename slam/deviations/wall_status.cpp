#include "slam/deviations/wall_status.hpp"

namespace isg::slam {

const char* toString(WallStatus status) {
  switch (status) {
    case WallStatus::kAsPlanned:
      return "as_planned";
    case WallStatus::kShifted:
      return "shifted";
    case WallStatus::kRotated:
      return "rotated";
    case WallStatus::kMissing:
      return "missing";
    case WallStatus::kNotSeen:
      break;
  }
  return "not_seen";
}

WallStatus decideWallStatus(const StatusEvidence& e, const DeviationOptions& options) {
  if (!e.has_evidence || e.observed_share < options.judged_share) {
    const double view_share =
        e.with_sight ? options.missing_sight_share : options.missing_view_share;
    const bool missing = e.observed_share < options.missing_seen_share && e.in_view_share &&
                         *e.in_view_share >= view_share &&
                         e.planned_length >= options.min_missing_length;
    return missing ? WallStatus::kMissing : WallStatus::kNotSeen;
  }
  if (!e.turned && !e.shifted) return e.undecided ? WallStatus::kNotSeen : WallStatus::kAsPlanned;
  if (e.most_observed < options.min_deviation_observations) return WallStatus::kNotSeen;
  return e.turned ? WallStatus::kRotated : WallStatus::kShifted;
}

}  // namespace isg::slam
