#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace isg::slam {

// Releasing plan walls that were not built where the plan draws them (docs/matching.md, "An
// imprecise plan"). Once localized, each held correspondence pulls its S-plane and the robot
// towards its planned surface, so a wall built 10 cm off pulls the map with it. Each held wall is
// judged against the others: the planar correction of P_T_M that best fits them (robustly, the
// wall left out) is applied, and what is left of its disagreement is its own. Beyond what a wall
// plane's noise explains, on several keyframes in a row, the wall is released.
struct WallReleaseOptions {
  // Beyond these, a wall's residual is its own deviation (the report's thresholds,
  // docs/deviations.md: the residuals of walls as planned stay within about a third of them).
  double distance = 0.06;   // m, along the planned normal at the middle of the seen segment
  double angle_deg = 1.5;   // between the S-plane's and the planned surface's normals
  double min_length = 1.0;  // m of the wall seen before it is judged, or counts for others
  // The others it is judged against: every other plan wall of the floor seen over min_length, at
  // least min_others of them, with normals in two directions. Judged only against its
  // neighbours within 6 m (the deviation report's neighbourhood), the generated buildings of
  // docs/deviations.md did worse, since the merge's window bends the map with the plan around a
  // wall built off.
  int min_others = 3;
  int strikes = 3;  // keyframes in a row beyond a threshold before it is released
  // A release holds on the stretch of the surface its S-plane was seen on and this far beyond
  // its ends (m: the gap of a doorway, across which association joins a wall's pieces).
  double stretch_margin = 1.0;
  // Residual scales of the correction's robust fit (Huber, then Cauchy, at 1 in these units).
  double sigma_distance = 0.03;  // m
  double sigma_angle_deg = 1.0;
};

// One held correspondence, in the plan frame P under the current P_T_M.
struct HeldWall {
  Eigen::Vector2d middle = Eigen::Vector2d::Zero();   // of the S-plane's seen segment
  double length = 0.0;                                // of that segment, m
  Eigen::Vector2d normal = Eigen::Vector2d::UnitX();  // the planned surface's, unit
  double offset = 0.0;  // signed distance of `middle` from the planned surface, m
  double angle = 0.0;   // S-plane's normal minus the planned surface's, wrapped, rad
  int wall = -1;        // the plan wall of the surface: its pieces and its two faces move together
};

struct WallResidual {
  bool judged = false;  // long enough, with enough others to judge it against
  double offset = 0.0;  // m, after the others' correction
  double angle = 0.0;   // rad, after the others' correction
  bool beyond(const WallReleaseOptions& options) const;
};

// Each wall's residual after the planar correction (x, y, yaw) that best fits the others: the
// weights of one robust fit over all walls, each plan wall counted once, and the judged wall's own
// plan wall then left out.
std::vector<WallResidual> residualsAgainstOthers(const std::vector<HeldWall>& walls,
                                                 const WallReleaseOptions& options);

// The planar correction (x, y, yaw about the origin of P) that the walls agree on, by the same
// robust fit: applied to P_T_M, what it leaves of each wall's residual is the fit's; none where
// the walls do not fix it (fewer than min_others plan walls, or normals one way only).
std::optional<Eigen::Vector3d> correctionOfAll(const std::vector<HeldWall>& walls,
                                               const WallReleaseOptions& options);

}  // namespace isg::slam
