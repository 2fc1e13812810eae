#pragma once

#include "common/pose_track.hpp"
#include "common/tum.hpp"

namespace isg::eval {

// The floor-plan localization score of the Hilti × Trimble SLAM Challenge 2026 (docs/
// evaluation.md, "The floor-plan score"): over the reference's poses from `skip` seconds after
// its first on, each pose scores 100 · e^(−decay · e), e the 2D distance in metres from the
// estimate at its stamp to it — the estimate's row at that stamp (within 1 ms), else its position
// interpolated between the rows either side when they are at most `max_gap` apart — and 0 when
// there is no estimate there (before the first, after the last, across a gap: lost);
// the run's score is the mean, and 0 when fewer than `min_coverage` of the poses have an
// estimate. At 1 m a pose scores 63.1, at 5 cm 97.7, at 1 cm 99.5.
struct FloorPlanScoreOptions {
  double decay = 0.4605;  // 1/m
  double skip = 5.0;      // s, not scored
  double min_coverage = 0.99;
  double max_gap = 0.25;  // s: rows further apart than this have no estimate between them
};

struct FloorPlanScore {
  double score = 0.0;     // 0 … 100
  double coverage = 0.0;  // share of the scored poses with an estimate
  int poses = 0;          // scored reference poses
};

FloorPlanScore floorPlanScore(common::PoseSequence reference, common::PoseSequence estimate,
                              const FloorPlanScoreOptions& options = {});

}  // namespace isg::eval
