#include "worlds/as_built.hpp"

#include <algorithm>

#include "bim/as_built_wall.hpp"

namespace isg::worlds {

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
