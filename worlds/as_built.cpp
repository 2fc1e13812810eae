#include "worlds/as_built.hpp"

#include <algorithm>

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
  for (const auto& shift : as_built.wall_shifts) {
    for (auto& wall : built.walls) {
      if (wall.id != shift.wall) continue;
      const Eigen::Vector2d axis = (wall.end - wall.start).normalized();
      const Eigen::Vector2d left(-axis.y(), axis.x());
      wall.start += shift.offset * left;
      wall.end += shift.offset * left;
    }
  }
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
