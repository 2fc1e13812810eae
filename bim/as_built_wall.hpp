#pragma once

#include "bim/plan.hpp"
#include "bim/scenario.hpp"

namespace isg::bim {

// Where a wall of the plan was built (docs/formats.md, `as_built`): turned about its start, centre,
// end or a point along it by its `wall_rotations` entry, then moved along its planned left normal
// by its `wall_shifts` entry. A wall with neither comes back as planned. Whether the wall was built
// at all
// (`missing_walls`) is the caller's to ask.
Wall builtWall(const Wall& planned, const AsBuilt& as_built);

// Where along the planned axis (metres from its start) a rotation turns the wall.
double rotationPivotAlong(const Wall& planned, const WallRotation& rotation);

// How far a built wall's axis lies from the planned one, measured as the deviation report measures
// an observed wall (docs/deviations.md): `offset_m` along the planned left normal, at the planned
// axis's centre; `angle_deg` from the planned direction to the built one, counter-clockwise, in
// (−90, 90]. A wall parallel to the plan has the same offset all along it.
struct AxisDeviation {
  double offset_m = 0.0;
  double angle_deg = 0.0;
};
AxisDeviation axisDeviation(const Wall& planned, const Eigen::Vector2d& built_point,
                            const Eigen::Vector2d& built_direction);

}  // namespace isg::bim
