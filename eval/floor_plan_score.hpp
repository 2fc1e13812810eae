#pragma once

#include <optional>
#include <vector>

#include "common/pose_track.hpp"
#include "common/tum.hpp"

namespace isg::eval {

// The floor-plan localization score of the Hilti × Trimble SLAM Challenge 2026 (docs/
// evaluation.md, "The floor-plan score"), as its repository states the rules:
// - the first `skip` seconds of the run are not scored: both trajectories from run start + skip
//   on (the run starts at `run_start`, default benchmarkRunStart(reference));
// - poses are associated as evo associates them (eval::associate, `max_diff` 10 ms: the
//   benchmark scores with evo), no interpolation;
// - the error is the 2D distance (z is not scored);
// - each associated pose scores a · e^(−c · error), a = 100, c = 0.46051701859880917 (100 at
//   0 m, 1 at 10 m); the run's score is their mean, capped at 100;
// - coverage = associated poses / reference poses scored; below 99 % the run scores 0.
struct FloorPlanScoreOptions {
  double scale = 100.0;                // a
  double decay = 0.46051701859880917;  // c, 1/m
  double skip = 5.0;                   // s, not scored
  double min_coverage = 0.99;
  double max_diff = 0.01;           // s
  std::optional<double> run_start;  // s, in the reference's clock
};

// Every recording of the benchmark starts at 10 000 s (its stamps are shifted by 10⁴ s), its
// reference a little later (the LiDAR starts after the camera): a reference whose first stamp is
// in [10 000, 10 000 + kBenchmarkClockWindow) s starts at 10 000 s; any other at its first stamp.
inline constexpr double kBenchmarkClockStart = 1e4;  // s
inline constexpr double kBenchmarkClockWindow = 60;  // s
double benchmarkRunStart(common::PoseSequence reference);

struct PoseScore {
  double t = 0.0;      // the reference pose's stamp
  double error = 0.0;  // m, in the plane
  double score = 0.0;  // a · e^(−c · error)
};

struct FloorPlanScore {
  double score = 0.0;     // 0 … 100
  double coverage = 0.0;  // associated poses / reference poses scored
  int poses = 0;          // reference poses scored (from run start + skip on)
  int associated = 0;
  double run_start = 0.0;
  std::vector<PoseScore> per_pose;  // in the reference's order
};

FloorPlanScore floorPlanScore(common::PoseSequence reference, common::PoseSequence estimate,
                              const FloorPlanScoreOptions& options = {});

// The estimate at each of the reference's stamps, as a submission to the benchmark holds it (one
// pose per camera frame): the estimate's row within 1 ms of the stamp, else its pose
// interpolated (position linearly, rotation by slerp) between the rows either side when they
// are at most `max_gap` apart; no pose across a longer gap (lost), before its first row or after
// its last.
inline constexpr double kResampleMaxGap = 0.25;  // s
common::Trajectory estimateAtStamps(common::PoseSequence reference, common::PoseSequence estimate,
                                    double max_gap = kResampleMaxGap);

// A run's own score (metrics.json): the benchmark's rule on its estimate resampled at the
// ground truth's stamps, as `isg run --submission` writes it.
FloorPlanScore runFloorPlanScore(common::PoseSequence ground_truth, common::PoseSequence estimate);

}  // namespace isg::eval
