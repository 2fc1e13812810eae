#include "worlds/walk_solids.hpp"

#include <cmath>

#include "bim/column.hpp"
#include "bim/plan_geometry.hpp"

namespace isg::worlds {

namespace {

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

// The planned wall a wall as built is, or is a part of ("ID#k", "ID##k", …: worlds::asBuiltLevel);
// "" for an extra wall.
std::string planWallOf(const bim::Level& plan_level, const std::string& built_id) {
  if (plan_level.findWall(built_id) != nullptr) return built_id;
  const std::size_t cut = built_id.find_last_not_of("0123456789");
  if (cut == std::string::npos || cut + 1 == built_id.size() || built_id[cut] != '#') return "";
  std::string stem = built_id.substr(0, cut + 1);
  while (!stem.empty() && stem.back() == '#') {
    stem.pop_back();
    if (plan_level.findWall(stem) != nullptr) return stem;
  }
  return "";
}

}  // namespace

WalkSolids::WalkSolids(const bim::Level& plan_level, const bim::Level& built_level,
                       const bim::AsBuilt& as_built) {
  const bim::LevelGeometry geometry = bim::computeLevelGeometry(built_level);
  for (const bim::WallGeometry& g : geometry.walls) {
    if (g.wall->base > kWalkerHeight) continue;
    // Rectangular columns follow the level's walls; a wall named a column (a plan from before
    // columns were their own element) is said to be one too.
    const bool named_column = g.wall->name.find("column") != std::string::npos;
    const std::string kind = g.column || named_column ? "column" : "wall";
    for (auto& piece : g.footprintPieces()) {
      WalkSolid solid;
      solid.outline = std::move(piece);
      solid.kind = g.column ? WalkSolid::Kind::kColumn : WalkSolid::Kind::kWall;
      solid.id = g.wall->id;
      solid.what = kind + " \"" + g.wall->id + "\"";
      solid.plan_id = g.column ? g.wall->id : planWallOf(plan_level, g.wall->id);
      solids_.push_back(std::move(solid));
    }
  }
  for (const auto& column : built_level.columns) {
    if (!column.round() || column.base > kWalkerHeight) continue;
    solids_.push_back({bim::columnFootprint(column), WalkSolid::Kind::kColumn, column.id,
                       "round column \"" + column.id + "\"", column.id});
  }
  for (std::size_t i = 0; i < as_built.clutter.size(); ++i) {
    const auto& c = as_built.clutter[i];
    if (c.level != built_level.id || c.center.z() - 0.5 * c.size.z() > kWalkerHeight) continue;
    const Eigen::Vector2d u(std::cos(c.yaw), std::sin(c.yaw)), v(-u.y(), u.x());
    const Eigen::Vector2d o = c.center.head<2>(), a = 0.5 * c.size.x() * u,
                          b = 0.5 * c.size.y() * v;
    solids_.push_back(
        {{o - a - b, o + a - b, o + a + b, o - a + b},
         WalkSolid::Kind::kClutter,
         "",
         "clutter box " + std::to_string(i) + " (/as_built/clutter/" + std::to_string(i) + ")",
         ""});
  }
  if (solids_.empty()) return;
  std::vector<bim::Box2> boxes;
  boxes.reserve(solids_.size());
  for (const auto& s : solids_) boxes.push_back(bim::Box2::around(s.outline));
  grid_.emplace(std::move(boxes));
}

std::optional<std::size_t> WalkSolids::solidAt(const Eigen::Vector2d& p) const {
  if (!grid_) return std::nullopt;
  for (int k : grid_->candidates(bim::Box2::around(p, p))) {
    if (deepInside(solids_[std::size_t(k)].outline, p, kWalkSolidTolerance)) return std::size_t(k);
  }
  return std::nullopt;
}

}  // namespace isg::worlds
