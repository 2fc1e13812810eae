#pragma once

#include <Eigen/Geometry>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bim/agraph.hpp"
#include "slam/deviations/column_deviations.hpp"
#include "slam/deviations/map_against_plan.hpp"
#include "slam/deviations/wall_progress.hpp"
#include "slam/map_diagnostics.hpp"

namespace isg::slam {

// As built against as planned (docs/deviations.md): once a map is placed in the plan, each plan
// wall of the levels the robot walked is compared with the map's walls in front of it. Every
// threshold is stated here and written to deviations.json with the report.
struct DeviationOptions {
  // A map wall is evidence for a plan surface facing the same way (normals within this angle)
  // when some point of it (an end or its middle) lies within `search_distance` of the surface's
  // plane and a third of it lies along the planned wall. Farther, it is an extra wall.
  double search_distance = 0.5;  // m
  double search_angle_deg = 20.0;
  double min_wall_length = 0.5;  // m: shorter map walls are not evidence
  // A map wall within this of a rectangular column's outline, all along, is a face of the column
  // (judged with the columns, slam::ColumnOptions::search_m alike), not an extra wall.
  double column_margin = 0.35;  // m
  // Judged deviating at or beyond these. Below them lies what the map's own noise explains: a
  // plane's offset to about 1 cm, its direction to a few tenths of a degree, the map's place in
  // the plan to 1–3 cm (docs/deviations.md, "Thresholds").
  double shift_m = 0.06;
  double angle_deg = 1.5;
  // Where the map is worse, so is the evidence: a wall is judged against the larger of those and
  // `noise_factor` times the map's own error around it — the length-weighted RMS of the offsets
  // (and, over walls at least min_angle_length long, the angles) the walls found as planned
  // within local_radius keep once the local placement is applied, scaled by √(n/(n−3)) for the
  // three numbers that placement fitted on their n walls (none with fewer than `min_noise_walls`).
  // Three times a normal error is passed by chance once in 370 walls. With fewer walls around,
  // the local placement rests on one or two of them and their own error moves it: a deviation
  // is then believed only when the level's placement (on all its walls) finds it too. The shift
  // threshold is also at least `noise_factor` times how well those walls fix the map across the
  // wall (the local placement's standard deviation along its normal: WallDeviation::
  // placement_sigma_m; the placement's 5 cm prior where none of them does).
  double noise_factor = 3.0;
  int min_noise_walls = 5;
  // A wall's evidence is consistent when both ends of a piece lie within this of the line its
  // pieces fit (the longest first); the others (a plane fitted across a corner, a door leaf)
  // are kept as evidence and not believed.
  double consistent_tolerance = 0.04;  // m
  // A long piece left out of that fit (at least half as long as the longest piece kept) makes
  // the wall's evidence contradict itself (two faces laid by the map a few cm apart) only when it
  // was observed at least this share as often as the most observed piece kept: a plane seen on
  // a keyframe or two, across a wall turned off the building's axes, is a stray fit, not a face.
  double contradiction_observation_share = 0.25;
  // A wall is called shifted or turned only when a piece of its consistent evidence was observed
  // from at least this many keyframes; a deviation seen on fewer is not believed and the wall is
  // `not_seen` (seen too little to judge). The plan is the prior: on the generated sites a plane
  // seen once or twice along a façade bay (a pallet's side before it, a glance across a corner)
  // was 5 of the 6 walls falsely reported off, while every one of the 148 walls reported off on
  // the office suites (all but one truly) was seen on 4 keyframes or more (docs/deviations.md,
  // "Statuses and thresholds").
  int min_deviation_observations = 3;
  // A direction is judged only from a map wall at least this long: a short plane's direction is
  // too loose to call a wall turned.
  double min_angle_length = 1.0;  // m
  // A wall is judged when its evidence covers this share of its length; less is `not_seen`, or
  // `missing` when next to nothing of it was seen (below `missing_seen_share`) though it lay in
  // the sensor's view over `missing_view_share` of its length.
  double judged_share = 0.2;
  double missing_seen_share = 0.05;
  double missing_view_share = 0.6;
  // When the keyframes recorded how far they saw (SightProfile), "in view" is "seen past": the
  // evidence of absence itself, which a wall standing there denies along every sight line it
  // stops. Near the wall's ends the sight lines past it meet the walls it joins within the margin,
  // so a missing wall between two offices is seen past over 55–60 % of its faces where geometry
  // had 60–70 % in view: this share stands for missing_view_share then.
  double missing_sight_share = 0.4;
  double min_missing_length = 1.0;  // m: a shorter wall is never called missing
  // In view: a point of a face within `view_range` of at least `min_views` keyframes standing in
  // front of it, at most `max_incidence_deg` off its normal, that saw past it: their farthest
  // return toward it lies beyond the wall's far face by `see_through_margin` (the map's place in
  // the plan to a few cm, a return's degree of azimuth 14 cm wide at view_range). Keyframes that
  // did not record how far they saw count when no other plan wall lies between.
  double view_range = 8.0;  // m
  double max_incidence_deg = 60.0;
  int min_views = 3;
  // The same margin tells a sight line blocked by a map wall (seenOnlyThroughWalls, for extra
  // walls seen from fewer than min_deviation_observations keyframes).
  double see_through_margin = 0.2;  // m
  // A wall's windows, widened by this each side (a degree of azimuth at view_range), are seen
  // through whether the wall stands or not: there only the map's walls say it is built.
  double window_margin = 0.15;  // m
  // A wall is placed by the final B_T_M unless the robot's poses in B when it saw the wall put
  // it farther than this from there (the map has bent since): then by those poses.
  double bend_distance = 0.05;  // m
  double bend_angle_deg = 0.5;
  // Each wall is measured after a placement fitted on the walls within this distance of it (and
  // not itself): the map bends a little over a long building.
  double local_radius = 6.0;  // m
  // Two opposite faces of extra walls at most this far apart are one wall.
  double extra_pair_distance = 0.4;  // m
  // A map wall seen from fewer than min_deviation_observations keyframes whose plane leans more
  // than this off vertical is a stray fit, not an extra wall: walls stand plumb, and a plane
  // fitted once from a keyframe whose attitude was off leans with it. On the four suites every
  // extra wall seen 3 times or more leaned at most 0.46°; the six seen once that leaned 1.0–2.7°
  // stood where nothing is (docs/deviations.md, "Extra walls").
  double max_stray_lean_deg = 1.0;
  // A turned wall's pivot (where its line crosses the planned axis) is named its start, centre or
  // end within this distance of it; elsewhere on the wall it is "along", off it "beyond" (a turn
  // and a shift together). The pivot is as loose as the offset over tan(angle): 1 cm of offset
  // at 2° moves it 0.29 m.
  double pivot_name_distance = 0.3;  // m
  // Progress (docs/deviations.md, "Progress"): each wall's exposed length sampled every
  // `progress_step`; a part in view with no map wall on it is not built when at least
  // `progress_gap_m` long. Shorter, the map cannot tell: a plane needs 100 voxels of 10 cm
  // (PlaneExtractionOptions::min_inliers), 0.4 m of a wall seen 2.5 m high, and a stretch between
  // a door and a wall meeting this one is found as a piece of its own or not at all. It stays
  // above the map's unconfirmed edge (ConfirmationOptions::near_m).
  double progress_step = 0.05;  // m
  double progress_gap_m = 0.6;  // m
};

enum class WallStatus { kAsPlanned, kShifted, kRotated, kMissing, kNotSeen };
const char* toString(WallStatus status);
inline bool deviates(WallStatus s) {
  return s == WallStatus::kShifted || s == WallStatus::kRotated || s == WallStatus::kMissing;
}

// One map wall taken as evidence for a plan wall, measured against the face it was seen as.
struct WallEvidence {
  int plane = -1;  // the map's plane id
  int side = +1;   // +1 the wall's left face, −1 its right face
  double length_m = 0.0;
  int observations = 0;
  double offset_m = 0.0;  // its line's, along the planned left normal, at the planned centre
  double angle_deg = 0.0;
  bool consistent = true;  // with the line the wall's pieces fit
  Eigen::Vector2d start_B = Eigen::Vector2d::Zero(), end_B = Eigen::Vector2d::Zero();
  // The parts of it its observations confirm (MapWall::confirmed), as shares of start → end;
  // empty: all of it. What progress counts as built.
  std::vector<std::pair<double, double>> confirmed;
};

struct WallDeviation {
  std::string wall;
  std::string level;
  WallStatus status = WallStatus::kNotSeen;
  // Of the line the consistent evidence fits (DeviationOptions::consistent_tolerance); none
  // without evidence.
  std::optional<double> offset_m, angle_deg;
  // Rotated walls: where along the planned axis (metres from its start) the wall's fitted line
  // crosses it, the point the wall turned about, and that point's name (start, centre, end,
  // along; beyond when it lies off the wall).
  std::optional<double> pivot_along_m;
  std::string turned_about;
  double observed_share = 0.0;  // of the planned length, covered by the evidence
  // What it was judged against (DeviationOptions::noise_factor), and the map's error around it
  // those follow (none where too few walls around were found as planned to tell).
  double shift_threshold_m = 0.0, angle_threshold_deg = 0.0;
  std::optional<double> local_offset_noise_m, local_angle_noise_deg;
  // How well the walls around fix where the map lies across this one (the standard deviation of
  // its local placement along the wall's normal, DeviationOptions::noise_factor).
  double placement_sigma_m = 0.0;
  std::optional<double> in_view_share;  // measured only for walls seen too little to judge
  Eigen::Vector2d planned_start = Eigen::Vector2d::Zero(), planned_end = Eigen::Vector2d::Zero();
  double thickness = 0.0;
  std::vector<WallEvidence> evidence;
  WallProgress progress;  // how much of it is built
};

// A wall the map has and the plan lacks: one face, or two opposite faces paired, in B.
struct ExtraWall {
  std::string level;
  Eigen::Vector2d start = Eigen::Vector2d::Zero(), end = Eigen::Vector2d::Zero();
  std::vector<int> planes;
  double length() const { return (end - start).norm(); }
};

// How the report moved the map on a level before judging its walls: B_T_M puts the map within the
// localizer's accuracy (1–3 cm), as much as the offsets to be measured; a best fit on the walls
// found as planned takes that error out (docs/deviations.md, "Placement").
struct PlacementCorrection {
  std::string level;
  Eigen::Vector3d correction =
      Eigen::Vector3d::Zero();  // x, y (m), yaw (rad) about the walls' centre
  int walls_used = 0;
};

struct DeviationReport {
  DeviationOptions options;
  std::vector<std::string> levels;              // the levels the robot walked, in the plan's order
  std::vector<PlacementCorrection> placements;  // one per level walked
  std::vector<WallDeviation> walls;
  std::vector<ExtraWall> extra_walls;
  // Where the map's points lie off the plan, per level walked (none when the points were not
  // measured: measureDeviations sees only the map's walls).
  std::vector<LevelAgainstPlan> against_plan;
  // The plan's columns on the levels walked, judged from the map's points (none when the points
  // were not given: measureDeviations sees only the map's walls; run/evaluate_run.cpp adds them).
  std::vector<ColumnDeviation> columns;
  ColumnOptions column_options;  // what they were judged by
  // Where each map keyframe stood in B for its sight lines ("seen past"; none: left out), as
  // viewpointsOnLevels takes them, so that the columns are judged from the same places.
  std::vector<std::optional<Eigen::Isometry3d>> keyframes_in_B;
  int count(WallStatus status) const;
};

// Where the line o(s) = offset + tan(angle)·s (s along a wall of `length` from its centre, o along
// its left normal) crosses the wall's axis, in metres from its start; none when it is parallel to
// within 1e-9 rad.
std::optional<double> crossingAlong(double length, double offset_m, double angle_deg);

// The name of a turned wall's pivot `along_m` from its start
// (DeviationOptions::pivot_name_distance).
std::string pivotName(double along_m, double length, double name_distance);

// The report of a map placed in the plan by B_T_M. Levels: those where a keyframe of the map
// stood. Walls of the plan only (a flight of stairs' faces explain map walls but are not judged).
// `keyframe_B_T_M`, when given (one per map keyframe, none where the robot was not localized):
// where the map lay in the plan as each keyframe was taken, i.e. the localizer's pose in B then
// composed with the keyframe's final pose in M. A long map bends, and the final B_T_M may put a
// wall seen long ago 10–30 cm off where the robot, localized then, had it right; or the robot
// was localized worse then than the final map is. A wall whose keyframes (up to the last 20 that
// saw it, their planar mean) place it more than bend_distance or bend_angle_deg from where B_T_M
// does is placed by whichever of the two lays the map's walls around it closer to the plan (the
// keyframes' when that cannot be told). Otherwise, and without them, B_T_M places it (it is the
// less noisy of the two where the map has not bent).
// The levels walked, and the sensor's places on each with what it saw past (keyed by the index of
// the floor in plan.floors): views from places 0.5 m apart (nearer ones add little to what is in
// view), each keyframe placed by `keyframes_in_B` (DeviationReport::keyframes_in_B; one per
// map.keyframes, none: left out). measureDeviations places a keyframe where it places the walls
// the keyframe saw: by B_T_M, or where most of them were placed by their keyframes
// (`keyframe_B_T_M`, as above) by the mean of those placements. A keyframe of a segment that
// ended (MapDiagnostics::current_segment) stands where the localizer had it then
// (`keyframe_B_T_M`), or is left out where it had none: B_T_M places the current segment's map.
// Either way, a sight line of a keyframe placed decimetres off would see past walls that stand.
std::map<int, std::vector<Viewpoint>> viewpointsOnLevels(
    const bim::AGraph& plan, const MapDiagnostics& map,
    const std::vector<std::optional<Eigen::Isometry3d>>& keyframes_in_B);

DeviationReport measureDeviations(
    const bim::AGraph& plan, const MapDiagnostics& map, const Eigen::Isometry3d& B_T_M,
    const DeviationOptions& options = {},
    const std::vector<std::optional<Eigen::Isometry3d>>& keyframe_B_T_M = {});

}  // namespace isg::slam
