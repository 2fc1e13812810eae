#pragma once

#include "common/pose_track.hpp"
#include "common/tum.hpp"

namespace isg::eval {

// How much of a run a global localizer was localized for (docs/evaluation.md). A localizer's
// estimate in B has rows only while it is localized, so: localized when it has any row; the time
// to first localization is the first estimate's stamp less the first ground-truth stamp; the share
// localized is the part of the ground truth's span from that first estimate to the end, less the
// time it was lost: gaps longer than `max_gap` between estimate rows, and the time after its last
// row when that is longer.
struct Coverage {
  bool localized = false;
  double time_to_first = 0.0;  // seconds (meaningless when not localized)
  double share = 0.0;          // 0 … 1
  double lost_seconds = 0.0;   // seconds without rows after the first one
};

Coverage localizationCoverage(common::PoseSequence ground_truth, common::PoseSequence estimate,
                              double max_gap = 1.0);

}  // namespace isg::eval
