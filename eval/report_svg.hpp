#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "common/pose_track.hpp"
#include "common/tum.hpp"

namespace isg::eval {

// What the building was as built, beside the plan: drawn over the plan's walls.
struct MapOverlay {
  enum class Kind { kExtraWall, kShiftedWall, kMissingWall, kClosedDoor, kClutter };
  Kind kind = Kind::kExtraWall;
  std::vector<Eigen::Vector2d> polygon;
};

// A room's name, placed near its centre where no path runs (within its outline when given).
struct RoomLabel {
  std::string text;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  std::vector<Eigen::Vector2d> outline;
};

// A trajectory the report reads where it lies, not a copy (a two-hour run's ground truth is
// 35 MB even as a common::PoseTrack): it must outlive the reportSvg call, so a temporary does not
// compile.
class TrajectoryView : public common::PoseSequence {
 public:
  TrajectoryView() = default;
  TrajectoryView(const common::Trajectory& trajectory)  // NOLINT: implicit, as a reference
      : common::PoseSequence(trajectory) {}
  TrajectoryView(const common::PoseTrack& track)  // NOLINT: implicit, as a reference
      : common::PoseSequence(track) {}
  TrajectoryView(common::Trajectory&&) = delete;
  TrajectoryView(common::PoseTrack&&) = delete;
};

// One storey of a building of several: its own map panel in the report, drawn with the parts of
// the trajectories whose height lies in [z_min, z_max) (each trajectory by its own z: an
// estimate on the wrong floor is drawn on that floor's panel).
struct StoreyPanel {
  std::string title;
  std::vector<std::vector<Eigen::Vector2d>> walls;
  std::vector<MapOverlay> overlays;
  std::vector<RoomLabel> labels;
  double z_min = 0.0, z_max = 0.0;
};

// A run's report as one SVG picture (plain data in, so that eval stays free of the plan model):
// the plan from above (walls with their door openings, the as-built changes, room names), the
// trajectories, where localization happened, a metre scale bar; below it the position error and
// the heading error over time, on round-number axes.
struct ReportInput {
  std::string title;
  std::vector<std::string> summary;  // lines printed under the title
  std::vector<std::vector<Eigen::Vector2d>> walls;
  std::vector<MapOverlay> overlays;
  std::vector<RoomLabel> labels;
  TrajectoryView ground_truth;
  TrajectoryView estimate;  // in B (from the first localized pose on), or aligned: see below
  std::string estimate_label = "estimate in B (once localized)";
  bool estimate_is_localization = true;  // false: an aligned SLAM estimate, drawn in another hue
  // The odometry, drawn faintly, each pose placed by `odometry_placement` when given (dead
  // reckoning: its frame M at the true start).
  TrajectoryView odometry;
  std::optional<Eigen::Isometry3d> odometry_placement;
  std::string error_title = "APE in B (2D, no alignment)";
  std::vector<std::pair<double, double>> error_over_time;          // (t, metres)
  std::vector<std::pair<double, double>> heading_error_over_time;  // (t, degrees)
  std::optional<double> localized_at;                              // seconds
  // The run's map placed in B (a thinned cloud), drawn as dots under the trajectories: how its
  // walls fall on the plan's.
  std::vector<Eigen::Vector3d> map_points;
  std::string empty_chart_text = "never localized";
  // A building of several storeys: one map panel per storey, stacked, instead of the single map
  // of walls, overlays and labels above.
  std::vector<StoreyPanel> storeys;
};

std::string reportSvg(const ReportInput& input);

// The report draws a map of `points` points (a panel's) as every reportDotStep(points)-th of them,
// at most ~20000 dots. A list already thinned so (fewer than 40000 points) is drawn whole: a long
// run's millions of map points need not be held to draw them.
std::size_t reportDotStep(std::size_t points);

}  // namespace isg::eval
