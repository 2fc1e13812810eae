#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bim/agraph.hpp"
#include "bim/plan.hpp"
#include "eval/tum.hpp"

namespace isg::cli {

// What one run of a localizer produced, from the loop (`isg run`) or a replay (`isg slam`).
struct RunRecord {
  std::string world;   // what the user named: a file or builtin:NAME, or the dataset folder
  std::string method;  // the localizer's name
  std::uint64_t seed = 0;
  const bim::Plan* plan = nullptr;  // for agraph.json and the report; may be null
  const bim::AGraph* agraph = nullptr;
  std::string level;
  eval::Trajectory ground_truth, odometry, estimate, estimate_map;
  std::optional<double> localized_at;  // stamp of the first pose in B
  int scans = 0;
  double sim_seconds = 0.0;
  double wall_seconds = 0.0;
  nlohmann::json graph;  // the localizer's final graph (sgraph.json)
};

// A run, evaluated once for metrics.json, the report and the summary.
struct RunEvaluation {
  // metrics.json: localization (when, share), APE in B (2D, no alignment, from the first
  // localized pose on — the paper's measure), the map-frame APE after SE(3) alignment, odometry
  // from the true start for comparison, speed. ALGORITHMS.md §7 and docs/evaluation.md.
  nlohmann::json metrics;
  eval::Trajectory dead_reckoning;                         // odometry from the true start, in B
  std::vector<std::pair<double, double>> error_over_time;  // (t, APE in B)
};
RunEvaluation evaluateRun(const RunRecord& run);

// Writes the run folder of ARCHITECTURE.md (groundtruth.tum, odometry.tum, estimate.tum,
// estimate_map.tum, metrics.json, agraph.json, sgraph.json, report.svg) all at once: into a
// temporary folder beside it, renamed into place at the end. An existing folder is an InputError
// unless `force`.
void writeRunFolder(const std::string& dir, const RunRecord& run, const RunEvaluation& evaluation,
                    bool force);

// The summary printed at the end of a run.
std::string runSummary(const std::string& command, const std::string& dir,
                       const nlohmann::json& metrics);

}  // namespace isg::cli
