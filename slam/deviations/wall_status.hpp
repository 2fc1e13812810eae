#pragma once

#include <optional>

#include "slam/deviations/deviation_options.hpp"

namespace isg::slam {

enum class WallStatus { kAsPlanned, kShifted, kRotated, kMissing, kNotSeen };
const char* toString(WallStatus status);
inline bool deviates(WallStatus s) {
  return s == WallStatus::kShifted || s == WallStatus::kRotated || s == WallStatus::kMissing;
}

// What decides a plan wall's status (docs/deviations.md, "Statuses and thresholds"): how much of
// it the map's walls cover, whether they lie off the plan beyond the thresholds (judged from the
// consistent evidence, and when the evidence contradicts itself from every long piece), how often
// the most observed consistent piece was seen, and for a wall seen too little how much of it was
// in view.
struct StatusEvidence {
  bool has_evidence = false;
  double observed_share = 0.0;  // of the planned length
  bool turned = false;          // |angle| at or beyond its threshold, from a piece long enough
  bool shifted = false;         // |offset| at or beyond its threshold
  int most_observed = 0;        // keyframes that saw the most observed consistent piece
  std::optional<double> in_view_share;  // measured only for walls seen too little to judge
  bool with_sight = false;      // the keyframes recorded how far they saw (missing_sight_share)
  double planned_length = 0.0;  // m
  // Beyond a threshold, but not clear of the measure's uncertainty (DeviationOptions::
  // clear_factor): not enough data to tell.
  bool undecided = false;
};

// The one place a wall's status is decided, row by row as the status table says:
//   - seen over less than judged_share (or no evidence): missing when seen over less than
//     missing_seen_share, at least min_missing_length long, and in view over missing_view_share
//     (missing_sight_share with sight lines); else not_seen;
//   - neither turned nor shifted: as_planned, or not_seen when a deviation beyond its threshold
//     was not clear of its uncertainty (undecided: not enough data);
//   - off the plan on evidence seen from fewer than min_deviation_observations keyframes:
//     not_seen (not believed);
//   - turned: rotated; else shifted.
WallStatus decideWallStatus(const StatusEvidence& evidence, const DeviationOptions& options);

}  // namespace isg::slam
