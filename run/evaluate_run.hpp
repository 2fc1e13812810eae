#pragma once

#include <utility>
#include <vector>

#include "eval/alignment.hpp"
#include "run/run_metrics.hpp"
#include "run/run_record.hpp"
#include "slam/deviations/plan_deviations.hpp"

namespace isg::run {

// A run, evaluated once for metrics.json, the report and the summary (docs/evaluation.md):
// localization (when, share), APE in B (2D, no alignment, from the first localized pose on —
// the paper's measure), the map-frame APE after SE(3) alignment, odometry from the true start for
// comparison, speed, and the method's search log.
struct RunEvaluation {
  RunMetrics metrics;
  // Dead reckoning (odometry from the true start): the run's odometry placed in B by this, when
  // there are odometry and ground truth. A placement, not a placed copy: hours of odometry are
  // ~50 MB.
  std::optional<Eigen::Isometry3d> dead_reckoning_B_T_M;
  std::vector<std::pair<double, double>> error_over_time;          // (t, APE in B, metres)
  std::vector<std::pair<double, double>> heading_error_over_time;  // (t, degrees)
  // The SE(3) alignment of the map-frame estimate to the ground truth, and the aligned
  // estimate's errors over time: what a method that never localizes in B (s-graph) is judged and
  // drawn by. The alignment, not an aligned copy (10 MB at two hours): the report of such a
  // method aligns its estimate when it draws it.
  std::optional<eval::Similarity> map_alignment;
  std::vector<std::pair<double, double>> map_error_over_time;
  std::vector<std::pair<double, double>> map_heading_error_over_time;
  // As built against as planned, for a map placed in a plan (deviations.json and .svg).
  std::optional<slam::DeviationReport> deviations;
};

RunEvaluation evaluateRun(const RunRecord& run);

}  // namespace isg::run
