#include "sim/walk_check.hpp"

#include <cstdio>
#include <string>

#include "common/input_error.hpp"
#include "worlds/as_built.hpp"
#include "worlds/walk_crossings.hpp"
#include "worlds/walk_solids.hpp"

namespace isg::sim {

void checkWalkClear(const bim::Scenario& scenario) {
  const bim::Route& route = scenario.robot.route;
  const bim::Level& plan_level = *scenario.plan.findLevel(scenario.robot.level);
  const bim::Level level = worlds::asBuiltLevel(plan_level, scenario.as_built);
  const worlds::WalkSolids solids(plan_level, level, scenario.as_built);
  if (solids.empty()) return;
  worlds::forEachWalkPoint(route.walk, [&](const Eigen::Vector2d& p, int line) {
    const auto k = solids.solidAt(p);
    if (!k) return true;
    const worlds::WalkSolid& solid = solids[*k];
    char where[96];
    std::snprintf(where, sizeof where, "the walk at (%.3f, %.3f) is inside ", p.x(), p.y());
    const std::string hint =
        solid.plan_id.empty()
            ? " (is the walk in the plan frame of robot.level? the scenario's as_built puts it "
              "there)"
            : " (is the walk in the plan frame of robot.level? a wall not built yet goes in "
              "as_built.missing_walls, one built in part in as_built.shortened_walls)";
    throw common::InputError(route.trajectory_file, "",
                             "line " + std::to_string(line) + ": " + where + solid.what +
                                 " on level \"" + level.id + "\" as built" + hint);
  });
}

}  // namespace isg::sim
