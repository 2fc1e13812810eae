#include "run/evaluate_run.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

#include "bim/floor_at.hpp"
#include "bim/polygon.hpp"
#include "common/version.hpp"
#include "eval/ape.hpp"
#include "eval/coverage.hpp"
#include "eval/wrong_localization.hpp"
#include "run/keyframe_placements.hpp"
#include "run/level_metrics.hpp"
#include "run/map_plan_error.hpp"
#include "run/map_to_plan_levels.hpp"

namespace isg::run {

namespace {

// How far the robot walked (2D, along the ground truth) until `until`, and how many plan rooms
// of the level it had stood in by then.
std::pair<double, int> walkedUntil(const common::PoseTrack& truth, double until,
                                   const bim::AGraph* plan, const std::string& level) {
  double distance = 0.0;
  std::set<int> rooms;
  for (std::size_t i = 0; i < truth.size() && truth.time(i) <= until; ++i) {
    const Eigen::Vector3d position = truth.position(i);
    const Eigen::Vector2d p = position.head<2>();
    if (i > 0) distance += (p - truth.position(i - 1).head<2>()).norm();
    if (plan == nullptr) continue;
    // The level stood on: the start level in a plan of one, the ground truth's in one of several.
    const int floor = plan->floors.size() > 1 ? bim::floorAt(*plan, position.z()) : -1;
    for (int r = 0; r < int(plan->rooms.size()); ++r) {
      const auto& room = plan->rooms[r];
      const bool on_level =
          floor >= 0 ? room.floor == floor
                     : level.empty() || room.floor < 0 || plan->floors[room.floor].id == level;
      if (on_level && !rooms.count(r) && bim::containsPoint(room.outline, p)) rooms.insert(r);
    }
  }
  return {distance, int(rooms.size())};
}

// Who made the run, and how long it took.
void identify(const RunRecord& run, RunMetrics& m) {
  const sensors::SensorStreams& streams = run.streams;
  m.world = run.setup.world;
  m.method = run.setup.method;
  m.seed = run.setup.seed;
  if (!run.setup.lidar_model.empty() && run.setup.lidar_model != "vlp16") {
    m.lidar_model = run.setup.lidar_model;
  }
  if (!run.setup.world_hash.empty()) m.world_hash = run.setup.world_hash;
  m.method_options = run.setup.method_options;
  m.build_version = common::buildVersion();
  m.scans = run.scans;
  m.sim_seconds = streams.duration;
  m.wall_seconds = run.wall_seconds;
  m.real_time_factor = run.wall_seconds > 0 ? streams.duration / run.wall_seconds : 0.0;
  RunTiming timing;
  for (const auto& [stage, seconds] : run.stage_times.stages())
    timing.stages.push_back({stage, seconds});
  timing.scans_read = run.scans_read;
  timing.localizer_seconds = run.localizer_seconds;
  timing.scan_wait_seconds = run.scan_wait_seconds;
  m.timing = timing;
}

// The measure, or a note saying why it could not be computed (no pose of the estimate near the
// ground truth's stamps, a map trajectory too short or straight to align).
template <typename Compute>
void attempt(RunMetrics& m, const char* what, const Compute& compute) {
  try {
    compute();
  } catch (const std::invalid_argument& e) {
    m.notes.push_back(std::string(what) + " not computed: " + e.what());
  }
}

// APE in B (2D, no alignment) and in M (SE(3)-aligned), with their errors over time.
void poseErrors(const RunRecord& run, const Trajectory& placed, RunEvaluation& evaluation) {
  RunMetrics& m = evaluation.metrics;
  const sensors::SensorStreams& streams = run.streams;
  eval::ErrorOptions planar;
  planar.align = eval::Alignment::kNone;
  planar.project_xy = true;
  if (!placed.empty()) {
    attempt(m, "APE in B", [&] {
      const auto ape = eval::absolutePoseError(streams.ground_truth, placed, planar);
      m.ape_B = ape.translation_stats;
      m.ape_B_rotation_deg = ape.rotation_stats;
      for (std::size_t i = 0; i < ape.translation.size(); ++i) {
        const double t = placed[ape.association.estimate[i]].t;
        evaluation.error_over_time.emplace_back(t, ape.translation[i]);
        evaluation.heading_error_over_time.emplace_back(t, ape.rotation_deg[i]);
      }
    });
  }
  if (run.estimate_map.size() >= 3) {
    eval::ErrorOptions se3 = planar;
    se3.align = eval::Alignment::kSE3;
    attempt(m, "APE in M (SE(3)-aligned)", [&] {
      const auto ape = eval::absolutePoseError(streams.ground_truth, run.estimate_map, se3);
      m.ape_M_se3 = ape.translation_stats;
      evaluation.map_alignment = ape.alignment;
      for (std::size_t i = 0; i < ape.translation.size(); ++i) {
        const double t = run.estimate_map[ape.association.estimate[i]].t;
        evaluation.map_error_over_time.emplace_back(t, ape.translation[i]);
        evaluation.map_heading_error_over_time.emplace_back(t, ape.rotation_deg[i]);
      }
    });
  }
}

// Each judged wall and column keeps the IFC GlobalId its plan element has, so that deviations.json
// and deviations.bcf name it as the model it was imported from does.
void keepGlobalIds(const bim::Plan& plan, slam::DeviationReport& report) {
  for (slam::WallDeviation& wall : report.walls) {
    const bim::Level* level = plan.findLevel(wall.level);
    const bim::Wall* planned = level ? level->findWall(wall.wall) : nullptr;
    if (planned) wall.ifc_guid = planned->ifc_guid;
  }
  for (slam::ColumnDeviation& column : report.columns) {
    const bim::Level* level = plan.findLevel(column.level);
    const bim::Column* planned = level ? level->findColumn(column.column) : nullptr;
    if (planned) column.ifc_guid = planned->ifc_guid;
  }
}

// The walls as built against the plan, from the map placed in it: where the map lay in the plan
// at each keyframe is the pose in B the localizer reported for that very scan (none while it was
// not localized: never interpolated across a gap), over the keyframe's final pose in M.
void deviations(const RunRecord& run, const std::vector<slam::LevelAgainstPlan>& against_plan,
                RunEvaluation& evaluation) {
  const std::vector<std::optional<Eigen::Isometry3d>> keyframe_B_T_M = keyframePlacements(run);
  evaluation.deviations =
      slam::measureDeviations(*run.setup.agraph, *run.map, *run.final_B_T_M, {}, keyframe_B_T_M);
  for (const std::string& level : evaluation.deviations->levels) {
    for (const auto& on : against_plan) {
      if (on.level == level) evaluation.deviations->against_plan.push_back(on);
    }
  }
  // The columns, from the map's points around them (one more pass over the points, on plans with
  // columns only) and the sight lines of the keyframes.
  if (run.setup.plan != nullptr) {
    slam::ColumnEvidence columns(*run.setup.plan, evaluation.deviations->levels,
                                 evaluation.deviations->column_options);
    if (columns.any()) {
      forEachPlacedMapPoint(run, [&](const Eigen::Vector3d& p) { columns.add(p); });
      evaluation.deviations->columns = columns.judge(
          *run.setup.agraph, slam::viewpointsOnLevels(*run.setup.agraph, *run.map,
                                                      evaluation.deviations->keyframes_in_B));
    }
  }
  if (run.setup.plan != nullptr) keepGlobalIds(*run.setup.plan, *evaluation.deviations);
  evaluation.metrics.deviations =
      deviationMetrics(*evaluation.deviations, run.setup.plan, run.setup.as_built);
}

// estimate.tum by state: its coverage, and per state its poses, APE in B and largest sigma; the
// keyframes keyframePlacements leaves unplaced because the plan did not confirm their pose.
RunMetrics::EstimateStates estimateStateMetrics(const RunRecord& run, bool has_truth) {
  RunMetrics::EstimateStates out;
  const sensors::SensorStreams& streams = run.streams;
  const common::PoseTrack& walk = has_truth ? streams.ground_truth : streams.odometry;
  const eval::Coverage coverage = eval::localizationCoverage(walk, run.estimate);
  out.coverage = coverage.share;
  if (coverage.localized && !walk.empty()) {
    const double span = walk.time(walk.size() - 1) - walk.time(0) - coverage.time_to_first;
    out.coverage_from_first =
        span > 0
            ? std::min(1.0, coverage.share * (walk.time(walk.size() - 1) - walk.time(0)) / span)
            : 1.0;
  }
  eval::ErrorOptions planar;
  planar.align = eval::Alignment::kNone;
  planar.project_xy = true;
  for (PoseState state : {PoseState::kLocalized, PoseState::kTracking, PoseState::kLost}) {
    const Trajectory poses = posesIn(run.estimate, run.estimate_states, {state});
    if (poses.empty()) continue;
    RunMetrics::EstimateStates::State& s = out.states.emplace_back();
    s.state = toString(state);
    s.poses = std::int64_t(poses.size());
    for (std::size_t i = 0; i < run.estimate_states.size(); ++i) {
      if (run.estimate_states[i].state == state) {
        s.max_sigma_xy = std::max(s.max_sigma_xy, run.estimate_states[i].sigma_xy);
      }
    }
    if (has_truth) {
      try {
        s.ape_B = eval::absolutePoseError(walk, poses, planar).translation_stats;
      } catch (const std::invalid_argument&) {
        // No pose of this state near a ground-truth stamp: no APE for it.
      }
    }
  }
  if (run.map) {
    // Of the segments that ended: the current one is placed by the final B_T_M.
    const auto placements = keyframePlacements(run);
    const std::size_t ended = std::min(run.map->current_segment, placements.size());
    for (std::size_t i = 0; i < ended; ++i) {
      if (placements[i]) continue;
      const auto row = std::lower_bound(
          run.estimate.begin(), run.estimate.end(), run.map->keyframes[i].stamp - 1e-3,
          [](const StampedPose& pose, double t) { return pose.t < t; });
      const bool had_pose =
          row != run.estimate.end() && std::abs(row->t - run.map->keyframes[i].stamp) <= 1e-3;
      if (had_pose) ++out.keyframes_left_out;
    }
  }
  return out;
}

// The matching's log: its status changes, and when it was lost and found again.
void matchingHistory(const RunRecord& run, RunMetrics& m) {
  m.matching_status = run.search_status;
  m.matching_events = run.status_changes;
  bool lost = false;
  for (const auto& change : run.status_changes) {
    if (change.status == slam::MatchStatus::kLost) {
      lost = true;
      m.lost_at.push_back(change.stamp);
    } else if (change.status == slam::MatchStatus::kMatched && lost) {
      lost = false;
      m.relocalized_at.push_back(change.stamp);
    }
  }
}

}  // namespace

RunEvaluation evaluateRun(const RunRecord& run) {
  RunEvaluation evaluation;
  RunMetrics& m = evaluation.metrics;
  const sensors::SensorStreams& streams = run.streams;
  identify(run, m);
  // The map against the plan first, while nothing else the evaluation makes is held (its
  // distances are the evaluation's largest temporary, ~25 MB at two hours); its note below.
  const MapPlanErrorOptions map_options;
  const std::optional<MapPlanError> map = mapPlanError(run, map_options);
  const bool has_truth = !streams.ground_truth.empty();
  if (!has_truth) m.notes.push_back("no ground truth: no APE (a dataset without groundtruth.tum)");
  // The poses the localizer placed (localized or tracking); the lost ones only count towards the
  // coverage of the estimate and the floor-plan score, which score whatever a run writes.
  const Trajectory placed =
      posesIn(run.estimate, run.estimate_states, {PoseState::kLocalized, PoseState::kTracking});
  m.estimate_states = estimateStateMetrics(run, has_truth);
  // Without ground truth, when the localizer first answered is still known from the odometry.
  const eval::Coverage coverage =
      eval::localizationCoverage(has_truth ? streams.ground_truth : streams.odometry, placed);
  m.localized = coverage.localized;
  if (coverage.localized) {
    m.time_to_localize = coverage.time_to_first;
    m.share_localized = coverage.share;
    if (has_truth) {
      const auto [distance, rooms] =
          walkedUntil(streams.ground_truth, streams.ground_truth.front().t + coverage.time_to_first,
                      run.setup.agraph, run.setup.level);
      m.distance_to_localize = distance;
      if (run.setup.agraph != nullptr) m.rooms_visited_to_localize = rooms;
    }
  }
  if (has_truth) poseErrors(run, placed, evaluation);
  if (has_truth && run.setup.agraph != nullptr) {
    m.levels =
        levelMetrics(*run.setup.agraph, streams.ground_truth, placed, evaluation.error_over_time);
  }
  // Dead reckoning: the odometry with its frame M placed at the true start pose.
  if (has_truth && !streams.odometry.empty()) {
    evaluation.dead_reckoning_B_T_M = sensors::trueStartB_T_M(streams);
    eval::ErrorOptions planar;
    planar.align = eval::Alignment::kNone;
    planar.project_xy = true;
    attempt(m, "APE of the odometry", [&] {
      m.ape_odometry_from_true_start =
          eval::absolutePoseError(streams.ground_truth, streams.odometry, planar,
                                  evaluation.dead_reckoning_B_T_M)
              .translation_stats;
    });
  }
  if (has_truth) {
    m.floor_plan_score = eval::runFloorPlanScore(streams.ground_truth, run.estimate);
  }
  if (has_truth && coverage.localized) {
    const eval::WrongLocalization wrong = eval::wrongLocalization(streams.ground_truth, placed);
    m.wrongly_localized = wrong.wrong;
    m.time_wrongly_localized = wrong.seconds;
    m.max_error_B = wrong.max_error;
    m.max_height_error_B = wrong.max_height_error;
  }
  // The map against the plan's walls: with or without ground truth, once the map was placed.
  // And where on each level the map lies off the plan (docs/deviations.md, "Where the map
  // disagrees with the plan"): every level of the plan measured, those with points reported.
  std::vector<slam::LevelAgainstPlan> against_plan;
  if (map) {
    m.map_to_plan = RunMetrics::MapToPlan{map->distance, std::int64_t(map->points), map->near_share,
                                          map_options.cutoff};
    std::vector<std::string> plan_levels;
    for (const auto& floor : run.setup.agraph->floors) plan_levels.push_back(floor.id);
    against_plan = mapAgainstPlan(run, plan_levels,
                                  {.cutoff_m = map_options.cutoff, .margin_m = map_options.margin});
    for (const auto& level : against_plan) {
      if (level.points > 0) m.map_to_plan->levels.push_back(levelSummary(level));
    }
  } else if (run.setup.agraph) {
    m.notes.push_back(
        run.final_B_T_M    ? "no map-to-plan error: no scan point in a wall's height band"
        : run.localized_at ? "no map-to-plan error, no as-built report: the run ended lost, and "
                             "a map the plan no longer places is not judged"
                           : "no map-to-plan error: the map was never placed in the plan");
  }
  if (run.map && run.final_B_T_M && run.setup.agraph != nullptr)
    deviations(run, against_plan, evaluation);
  matchingHistory(run, m);
  return evaluation;
}

}  // namespace isg::run
