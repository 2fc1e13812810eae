#include "worlds/as_built.hpp"

#include <algorithm>
#include <optional>
#include <vector>

#include "bim/as_built_wall.hpp"

namespace isg::worlds {
namespace {

// Replaces the wall by the parts of it that stand, `ID#1`, `ID#2`, … (`ID##1` … should the plan
// have a wall of that id), each from its own start; its doors and windows move to the part they
// are in, or go with a part not built.
void shortenWall(bim::Level& level, const bim::ShortenedWall& shortened) {
  const auto it = std::find_if(level.walls.begin(), level.walls.end(),
                               [&](const bim::Wall& w) { return w.id == shortened.wall; });
  if (it == level.walls.end()) return;  // another level's wall
  const bim::Wall wall = *it;
  const Eigen::Vector2d along = (wall.end - wall.start).normalized();
  std::string stem = wall.id + "#";
  const auto taken = [&](const std::string& prefix) {
    return std::any_of(level.walls.begin(), level.walls.end(),
                       [&](const bim::Wall& w) { return w.id.rfind(prefix, 0) == 0; });
  };
  while (taken(stem)) stem += "#";
  std::vector<bim::Wall> parts;
  for (std::size_t k = 0; k < shortened.built.size(); ++k) {
    bim::Wall part = wall;
    part.id = stem + std::to_string(k + 1);
    part.start = wall.start + shortened.built[k].first * along;
    part.end = wall.start + shortened.built[k].second * along;
    parts.push_back(part);
  }
  // Which part an opening centred `offset` along the wall is in, and where along it; none when
  // it lies in a part not built.
  const auto partOf = [&](double offset) -> std::optional<std::size_t> {
    for (std::size_t k = 0; k < shortened.built.size(); ++k) {
      if (offset >= shortened.built[k].first && offset <= shortened.built[k].second) return k;
    }
    return std::nullopt;
  };
  const auto moveOpening = [&](auto& openings) {
    std::erase_if(openings, [&](auto& opening) {
      if (opening.wall != wall.id) return false;
      const auto k = partOf(opening.offset);
      if (!k) return true;
      opening.wall = parts[*k].id;
      opening.offset -= shortened.built[*k].first;
      return false;
    });
  };
  moveOpening(level.doors);
  moveOpening(level.windows);
  const auto at = level.walls.erase(it);
  level.walls.insert(at, parts.begin(), parts.end());
}

}  // namespace

bim::Level asBuiltLevel(const bim::Level& level, const bim::AsBuilt& as_built) {
  bim::Level built = level;
  auto is_missing = [&](const std::string& wall_id) {
    return std::find(as_built.missing_walls.begin(), as_built.missing_walls.end(), wall_id) !=
           as_built.missing_walls.end();
  };
  std::erase_if(built.walls, [&](const bim::Wall& w) { return is_missing(w.id); });
  std::erase_if(built.doors, [&](const bim::Door& d) { return is_missing(d.wall); });
  std::erase_if(built.windows, [&](const bim::Window& w) { return is_missing(w.wall); });
  for (auto& wall : built.walls) wall = bim::builtWall(wall, as_built);
  std::erase_if(built.columns, [&](const bim::Column& c) {
    return std::find(as_built.missing_columns.begin(), as_built.missing_columns.end(), c.id) !=
           as_built.missing_columns.end();
  });
  for (auto& column : built.columns) {
    for (const auto& move : as_built.moved_columns) {
      if (move.column == column.id) column.center += move.offset;
    }
  }
  for (const auto& shortened : as_built.shortened_walls) shortenWall(built, shortened);
  for (const auto& extra : as_built.extra_walls) {
    if (extra.level != level.id) continue;
    bim::Wall wall;
    wall.id = extra.id;
    wall.start = extra.start;
    wall.end = extra.end;
    wall.thickness = extra.thickness;
    wall.height = extra.height.value_or(level.height);
    wall.base = extra.base;
    built.walls.push_back(wall);
  }
  return built;
}

}  // namespace isg::worlds
