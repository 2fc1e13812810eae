#pragma once

#include <string>

#include "bim/plan.hpp"
#include "bim/scenario.hpp"

namespace isg::worlds {

// Geom groups of a generated world. mj_ray and the renderer filter by group, so the building,
// its ceilings (hidden in top-down pictures) and the robot (never seen by its own LiDAR) each
// have their own.
inline constexpr int kBuildingGroup = 1;
inline constexpr int kCeilingGroup = 2;
inline constexpr int kRobotGroup = 3;

struct WorldOptions {
  double slab_thickness = 0.1;        // floor and ceiling slabs
  double door_leaf_thickness = 0.04;  // a closed door's leaf, centred in the wall
  double floor_margin = 1.0;          // the floor slab reaches this far past the outer walls
  bool ceilings = true;
  // MJCF inserted at the end of <worldbody> (the simulator's robot); the building never needs it.
  std::string extra_worldbody;
};

// Generates the MuJoCo MJCF of a building: the plan with the scenario's as-built deviations.
// Geoms are named after the plan's ids:
//   wall/<wall>/<k>           k-th solid piece of a wall (pieces are split by door openings)
//   wall/<wall>/lintel/<door> the part of the wall above a door
//   door/<door>               the leaf of a closed door
//   floor/<level>, ceiling/<level>, clutter/<k>, and wall/extra<k>/... for extra walls
// and rooms carry a site room/<room> at their centroid. Building geoms are in kBuildingGroup,
// ceilings in kCeilingGroup. The result compiles with mj_loadXML in MuJoCo 2.2.2.
std::string generateMjcf(const bim::Plan& plan, const bim::AsBuilt& as_built = {},
                         const WorldOptions& options = {});

inline std::string generateMjcf(const bim::Scenario& scenario, const WorldOptions& options = {}) {
  return generateMjcf(scenario.plan, scenario.as_built, options);
}

}  // namespace isg::worlds
