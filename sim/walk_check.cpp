#include "sim/walk_check.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bim/box_grid.hpp"
#include "bim/column.hpp"
#include "bim/plan_geometry.hpp"
#include "common/input_error.hpp"
#include "worlds/as_built.hpp"

namespace isg::sim {

namespace {

// A walker's head clears a wall hung this high above the floor (a beam, a bulkhead).
constexpr double kWalkerHeight = 1.9;  // m

struct Solid {
  std::vector<Eigen::Vector2d> outline;  // convex, counter-clockwise
  std::string what;                      // "wall \"W3\"", "clutter box 2"
};

// Inside the convex CCW outline by more than `margin` from every edge.
bool deepInside(const std::vector<Eigen::Vector2d>& outline, const Eigen::Vector2d& p,
                double margin) {
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const Eigen::Vector2d& a = outline[i];
    const Eigen::Vector2d& b = outline[(i + 1) % outline.size()];
    const Eigen::Vector2d edge = b - a;
    const double length = edge.norm();
    if (length < 1e-12) continue;
    const double left = (edge.x() * (p.y() - a.y()) - edge.y() * (p.x() - a.x())) / length;
    if (left <= margin) return false;
  }
  return true;
}

}  // namespace

void checkWalkClear(const bim::Scenario& scenario) {
  const bim::Route& route = scenario.robot.route;
  const bim::Level& plan_level = *scenario.plan.findLevel(scenario.robot.level);
  const bim::Level level = worlds::asBuiltLevel(plan_level, scenario.as_built);
  const bim::LevelGeometry geometry = bim::computeLevelGeometry(level);
  std::vector<Solid> solids;
  for (std::size_t w = 0; w < geometry.walls.size(); ++w) {
    const bim::WallGeometry& g = geometry.walls[w];
    if (g.wall->base > kWalkerHeight) continue;
    // Rectangular columns follow the level's walls; a wall named a column (a plan from before
    // columns were their own element) is said to be one too.
    const bool column = g.column || g.wall->name.find("column") != std::string::npos;
    const std::string kind = column ? "column" : "wall";
    for (auto& piece : g.footprintPieces()) {
      solids.push_back({std::move(piece), kind + " \"" + g.wall->id + "\""});
    }
  }
  for (const auto& column : level.columns) {
    if (!column.round() || column.base > kWalkerHeight) continue;
    solids.push_back({bim::columnFootprint(column), "round column \"" + column.id + "\""});
  }
  for (std::size_t i = 0; i < scenario.as_built.clutter.size(); ++i) {
    const auto& c = scenario.as_built.clutter[i];
    if (c.level != level.id || c.center.z() - 0.5 * c.size.z() > kWalkerHeight) continue;
    const Eigen::Vector2d u(std::cos(c.yaw), std::sin(c.yaw)), v(-u.y(), u.x());
    const Eigen::Vector2d o = c.center.head<2>(), a = 0.5 * c.size.x() * u,
                          b = 0.5 * c.size.y() * v;
    solids.push_back(
        {{o - a - b, o + a - b, o + a + b, o - a + b},
         "clutter box " + std::to_string(i) + " (/as_built/clutter/" + std::to_string(i) + ")"});
  }
  if (solids.empty()) return;
  std::vector<bim::Box2> boxes;
  boxes.reserve(solids.size());
  for (const auto& s : solids) boxes.push_back(bim::Box2::around(s.outline));
  const bim::BoxGrid grid(std::move(boxes));
  for (const auto& pose : route.walk) {
    for (int k : grid.candidates(bim::Box2::around(pose.xy, pose.xy))) {
      if (!deepInside(solids[std::size_t(k)].outline, pose.xy, kWalkSolidTolerance)) continue;
      char where[96];
      std::snprintf(where, sizeof where, "the walk at (%.3f, %.3f) is inside ", pose.xy.x(),
                    pose.xy.y());
      throw common::InputError(
          route.trajectory_file, "",
          "line " + std::to_string(pose.line) + ": " + where + solids[std::size_t(k)].what +
              " on level \"" + level.id +
              "\" as built (is the walk in the plan frame of robot.level? a wall not built yet "
              "goes in as_built.missing_walls, one built in part in as_built.shortened_walls)");
    }
  }
}

}  // namespace isg::sim
