#pragma once

#include <Eigen/Geometry>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bim/agraph.hpp"
#include "slam/deviations/column_deviations.hpp"
#include "slam/deviations/deviation_options.hpp"
#include "slam/deviations/map_against_plan.hpp"
#include "slam/deviations/wall_progress.hpp"
#include "slam/deviations/wall_status.hpp"
#include "slam/map_diagnostics.hpp"

namespace isg::slam {

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
  std::string ifc_guid;  // the plan wall's IFC GlobalId (bim::Wall::ifc_guid); "" when none
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
  // And how well they fix its direction (the local placement's yaw, standard deviation).
  double placement_angle_sigma_deg = 0.0;
  // The uncertainty of each measure (DeviationOptions::end_sigma_m): standard deviations of the
  // offset and angle (the fitted line's from its evidence, with the placement's), and of a
  // turned wall's pivot along the wall. None without evidence (or without a pivot).
  std::optional<double> offset_sigma_m, angle_sigma_deg, pivot_sigma_m;
  // The fitted line's own covariance of (offset, slope) (not in deviations.json; for the pivot's).
  Eigen::Matrix2d fit_covariance = Eigen::Matrix2d::Zero();
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
