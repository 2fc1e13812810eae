#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "bim/box_grid.hpp"
#include "bim/plan.hpp"
#include "bim/scenario.hpp"

namespace isg::worlds {

// What stands in a walker's way on a level as built (docs/simulation.md, "Replayed walks"):
// each wall's solid piece between its doorways, each column, each clutter box. Walls whose base
// is above kWalkerHeight (a beam, a bulkhead) do not count.
inline constexpr double kWalkerHeight = 1.9;  // m
// A walker passes closer to a wall than a planned route's clearance: a point counts as inside a
// solid only when it is more than this far from every edge of it.
inline constexpr double kWalkSolidTolerance = 0.02;  // m

struct WalkSolid {
  enum class Kind { kWall, kColumn, kClutter };
  std::vector<Eigen::Vector2d> outline;  // convex, counter-clockwise
  Kind kind = Kind::kWall;
  std::string id;    // the wall's id as built ("W5", "W5#2"), the column's, "" for clutter
  std::string what;  // for messages: "wall \"W3\"", "round column \"C2\"", "clutter box 2 (…)"
  // The plan's wall or column this is (of), "" for an as_built extra wall and for clutter.
  std::string plan_id;
};

// The solids of `built_level` (the level as built, worlds::asBuiltLevel) and of the clutter of
// `as_built` on it, indexed for point queries.
class WalkSolids {
 public:
  WalkSolids(const bim::Level& plan_level, const bim::Level& built_level,
             const bim::AsBuilt& as_built);

  // The first solid (in the order walls, columns, clutter) that `p` lies deep inside.
  std::optional<std::size_t> solidAt(const Eigen::Vector2d& p) const;
  const WalkSolid& operator[](std::size_t i) const { return solids_[i]; }
  bool empty() const { return solids_.empty(); }

 private:
  std::vector<WalkSolid> solids_;
  std::optional<bim::BoxGrid> grid_;
};

}  // namespace isg::worlds
