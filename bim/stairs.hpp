#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "bim/plan.hpp"

namespace isg::bim {

// What a plan's stairs must be for a legged robot to take them (docs/formats.md, "Stairs"). The
// step rise is derived: the fewest equal steps of at most kMaxStepRise. The slope limit is that
// of the steepest stairs building codes allow for homes (rise 0.2 m over a going of 0.22 m,
// 42.3°), which Spot-class robots are sold to climb; the width is a 0.5 m wide body with 5 cm on
// either side.
inline constexpr double kMaxStepRise = 0.2;
inline constexpr double kMaxStairSlope = 0.2 / 0.22;  // rise over run
inline constexpr double kMinStairWidth = 0.6;
// The clear height kept over a flight (building codes ask 2.0 m over stairs; a legged robot with
// its LiDAR stands about 1 m): the upper level's floor is open over the part of the flight that
// rises within this of it, and stands over the rest.
inline constexpr double kStairHeadroom = 2.0;

// A flight's derived geometry, in B: a plan's Stair between the elevations of its two levels.
struct StairGeometry {
  const Stair* stair = nullptr;
  Eigen::Vector2d axis = Eigen::Vector2d::UnitX();         // unit, start → end
  Eigen::Vector2d left_normal = Eigen::Vector2d::UnitY();  // axis turned +90°
  double run = 0.0;                                        // horizontal length, start → end
  double z_start = 0.0;  // floor elevation at the flight's `start` edge
  double z_end = 0.0;    // ... and at its `end` edge (above or below z_start)
  int steps = 0;         // equal steps, each of rise |z_end − z_start| / steps
  double step_rise = 0.0;
  double going = 0.0;  // run / steps: the depth of one step

  double rise() const { return std::abs(z_end - z_start); }
  double slope() const { return rise() / run; }
  // The flight's footprint as a CCW rectangle.
  std::vector<Eigen::Vector2d> footprint() const;
  // The part of it the upper level's floor is open over (the stairwell): from the upper edge back
  // along the flight as far as it rises within kStairHeadroom of the upper floor (the whole
  // flight when it rises less than that).
  std::vector<Eigen::Vector2d> openingFootprint() const;
  // Where a point lies along the flight: 0 at `start`, `run` at `end` (unclamped), and across it.
  double along(const Eigen::Vector2d& point) const { return (point - stair->start).dot(axis); }
  double across(const Eigen::Vector2d& point) const {
    return (point - stair->start).dot(left_normal);
  }
  bool contains(const Eigen::Vector2d& point, double margin = 0.0) const;
  // The ground height a walking body follows at distance `s` along the flight (clamped to it):
  // the straight line from the floor at `start` to the floor at `end`, which the feet average
  // over the steps (the treads lie at most one step rise above it).
  double walkLineZ(double s) const;
  // Step k (0 = the one at `start`): its extent [s0, s1] along the flight and its tread's height.
  struct Step {
    double s0, s1, top;
  };
  Step step(int k) const;
};

// The geometry of `stair`, which lies on level `from` and leads to level `to`.
StairGeometry computeStairGeometry(const Stair& stair, const Level& from, const Level& to);

// The corners of a wall's footprint (its axis ± half the thickness, without the joint
// extensions), CCW.
std::vector<Eigen::Vector2d> wallRectangle(const Wall& wall);

// Whether two convex polygons share interior points: they overlap by more than `tolerance`
// (touching along an edge is not overlapping).
bool convexPolygonsOverlap(const std::vector<Eigen::Vector2d>& a,
                           const std::vector<Eigen::Vector2d>& b, double tolerance);

}  // namespace isg::bim
