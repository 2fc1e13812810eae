#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "eval/ape.hpp"
#include "eval/floor_plan_score.hpp"
#include "run/deviation_grading.hpp"
#include "slam/map_diagnostics.hpp"

namespace isg::run {

using eval::Statistics;

// Where a run's time went (metrics.json `timing`, `isg run --timing`; docs/performance.md).
struct RunTiming {
  struct Stage {
    std::string stage;
    double seconds = 0.0;  // CPU seconds, summed over threads
  };
  std::vector<Stage> stages;             // the scan source's, the localizer's, then the evaluation
  int scans_read = 0;                    // the localizer skipped the others: they were never made
  double localizer_seconds = 0.0;        // wall time in the localizer's calls
  double scan_wait_seconds = 0.0;        // wall time the loop waited for scans
  std::optional<double> peak_memory_mb;  // the process's peak resident set
};

// One storey of a run in a plan of several (metrics.json `levels`): where the ground truth stood
// on that level (the level with the highest elevation at or below the robot's base; on a flight
// the level it climbs from until its base passes the next one's floor).
struct LevelMetrics {
  std::string level;                        // the plan's level id
  double seconds = 0.0;                     // of ground truth on it
  double arrived_at = 0.0;                  // s from the first ground-truth stamp: first there
  std::optional<double> first_estimate_at;  // s from the first ground-truth stamp
  std::optional<Statistics> ape_B;          // the APE in B rows whose ground truth is on it
};

// A run's measures: what metrics.json holds (docs/evaluation.md names every field). Typed here;
// JSON only where the file is written or read (metricsToJson, readMetrics), so `isg run`,
// `isg slam`, `isg table` and the report share one spelling of each name.
struct RunMetrics {
  std::string world;   // what the user named (file, builtin:NAME or dataset folder)
  std::string method;  // the localizer's name
  std::uint64_t seed = 0;
  // The content hash of the world (worlds::worldHash), when the run had one: isg table and
  // isg sweep never mix runs of different worlds that share a name.
  std::optional<std::string> world_hash;
  // The simulated LiDAR when it is not the VLP-16 (absent: a VLP-16, or a replayed dataset).
  std::optional<std::string> lidar_model;
  // What made the run: the method's options with the values it used (given or default; empty
  // for a method without options), and the build of isg (common::buildVersion). Absent from
  // metrics written before they were recorded.
  std::optional<std::map<std::string, double>> method_options;
  std::optional<std::string> build_version;
  int scans = 0;
  double sim_seconds = 0.0;   // robot time
  double wall_seconds = 0.0;  // wall-clock time of the loop
  double real_time_factor = 0.0;
  bool localized = false;
  std::optional<double> time_to_localize;  // s from the first ground-truth stamp
  // By then (with ground truth): metres walked (2D) and plan rooms of the level stood in.
  std::optional<double> distance_to_localize;
  std::optional<int> rooms_visited_to_localize;
  std::optional<double> share_localized;  // of the ground truth's span, 0 … 1
  std::optional<Statistics> ape_B;        // 2D, no alignment, from the first localized pose on
  std::optional<Statistics> ape_B_rotation_deg;
  std::optional<Statistics> ape_M_se3;                     // the map-frame estimate, SE(3)-aligned
  std::optional<Statistics> ape_odometry_from_true_start;  // dead reckoning, for comparison
  // Wrong localization (eval/wrong_localization.hpp): rows more than 1 m off in the plane or in
  // height (another floor); the run is wrong when they last longer than 5 s on end. With ground
  // truth and a localized run only.
  std::optional<bool> wrongly_localized;
  std::optional<double> time_wrongly_localized;  // s
  std::optional<double> max_error_B;             // m, the largest 2D error of any row in B
  std::optional<double> max_height_error_B;      // m, the largest height error of any row in B
  // The Hilti × Trimble challenge's floor-plan localization score (eval/floor_plan_score.hpp),
  // with ground truth only: 0 … 100, its coverage and the poses it scored.
  std::optional<eval::FloorPlanScore> floor_plan_score;
  // estimate.tum by its poses' states (run/estimate_states.hpp; docs/evaluation.md, "An estimate
  // for every scan"): the share of the walk's span (ground truth, else odometry) with a pose of
  // any state, and of the span from the first pose on (gaps over 1 s are uncovered); per state
  // with poses, how many, their APE in B (with ground truth) and their largest stated sigma; and
  // how many of the map's keyframes the as-built report and the map-to-plan measure left out
  // because the plan did not confirm their pose.
  struct EstimateStates {
    double coverage = 0.0;
    double coverage_from_first = 0.0;
    struct State {
      std::string state;  // "localized", "tracking", "lost"
      std::int64_t poses = 0;
      std::optional<Statistics> ape_B;
      double max_sigma_xy = 0.0;
    };
    std::vector<State> states;
    std::int64_t keyframes_left_out = 0;
  };
  std::optional<EstimateStates> estimate_states;
  // The map against the plan's walls (run/map_plan_error.hpp), with or without ground truth: the
  // distances of the points near the plan, how many points lay in a wall's height band, the share
  // of them near the plan, and the cutoff that "near" means.
  struct MapToPlan {
    Statistics distance;
    std::int64_t points = 0;
    double near_share = 0.0;
    double cutoff = 0.0;
    // The same per level the map has points on (docs/deviations.md, "Where the map disagrees
    // with the plan"), so that a floor that localizes worse says where: its near points' median
    // and 95th percentile distance (to the millimetre), the face stretches measured, those lying
    // off (|signed mean| of 4 cm or more: run/map_to_plan_levels.hpp) and their length, and the
    // farthest stretch.
    struct Level {
      std::string level;
      std::int64_t points = 0;
      double near_share = 0.0;
      double median_m = 0.0, p95_m = 0.0;
      int stretches = 0;
      int off_stretches = 0;
      double off_length_m = 0.0;
      struct Farthest {
        std::string surface;
        double mean_m = 0.0;
        Eigen::Vector2d start = Eigen::Vector2d::Zero(), end = Eigen::Vector2d::Zero();
      };
      std::optional<Farthest> farthest;
    };
    std::vector<Level> levels;
  };
  std::optional<MapToPlan> map_to_plan;
  // As built against as planned (deviations.json), graded when the building's truth is known.
  std::optional<DeviationMetrics> deviations;
  std::optional<std::string> matching_status;  // methods that search for a match
  std::vector<slam::StatusChange> matching_events;
  // Stamps where the search status became "lost", and where it became "matched" again after.
  std::vector<double> lost_at;
  std::vector<double> relocalized_at;
  std::vector<LevelMetrics> levels;  // plans of several levels, with ground truth
  std::optional<RunTiming> timing;
  // Why a measure is missing ("no ground truth: no APE", "APE in M … not computed: …").
  std::vector<std::string> notes;
};

nlohmann::json metricsToJson(const RunMetrics& metrics);
// Reads metrics.json's content; a missing or mistyped field is an InputError naming `file` and
// the field's JSON pointer.
RunMetrics metricsFromJson(const nlohmann::json& document, const std::string& file);
// RUN_DIR/metrics.json, read and checked.
RunMetrics readMetrics(const std::string& run_dir);

// The file name inside a run folder.
inline constexpr const char* kMetricsFile = "metrics.json";

}  // namespace isg::run
