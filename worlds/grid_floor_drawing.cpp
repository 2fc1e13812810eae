#include "worlds/grid_floor_drawing.hpp"

#include "worlds/millimetres.hpp"

namespace isg::worlds {

GridFloorDrawing::GridFloorDrawing(std::uint64_t stream_seed, double height) : rng_(stream_seed) {
  level.id = "L0";
  level.height = height;
}

void GridFloorDrawing::addPlacedWall(const std::string& id, const Eigen::Vector2d& a,
                                     const Eigen::Vector2d& b, double thickness,
                                     const std::string& name) {
  bim::Wall wall;
  wall.id = id;
  wall.start = {mm(a.x()), mm(a.y())};
  wall.end = {mm(b.x()), mm(b.y())};
  wall.thickness = thickness;
  wall.height = level.height;
  wall.name = name;
  level.walls.push_back(wall);
  solids.push_back({wall.start, wall.end, thickness});
}

std::size_t GridFloorDrawing::addPlacedColumn(const Eigen::Vector2d& centre, double width,
                                              bool round) {
  bim::Column pillar;
  pillar.id = "C" + std::to_string(level.columns.size() + 1);
  pillar.center = {mm(centre.x()), mm(centre.y())};
  pillar.size = {width, width};
  if (round) pillar.shape = bim::Column::Shape::kRound;
  pillar.height = level.height;
  pillar.name = "column";
  level.columns.push_back(pillar);
  solids.push_back({pillar.center - Eigen::Vector2d(0.5 * width, 0),
                    pillar.center + Eigen::Vector2d(0.5 * width, 0), width});
  return level.columns.size() - 1;
}

}  // namespace isg::worlds
