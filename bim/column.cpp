#include "bim/column.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace isg::bim {

Wall columnWall(const Column& column) {
  const Eigen::Vector2d along(std::cos(column.yaw), std::sin(column.yaw));
  Wall wall;
  wall.id = column.id;
  wall.start = column.center - 0.5 * column.size.x() * along;
  wall.end = column.center + 0.5 * column.size.x() * along;
  wall.thickness = column.size.y();
  wall.height = column.height;
  wall.base = column.base;
  wall.name = column.name;
  return wall;
}

std::vector<Eigen::Vector2d> columnFootprint(const Column& column, int sides) {
  std::vector<Eigen::Vector2d> outline;
  if (!column.round()) {
    const Eigen::Vector2d u =
        0.5 * column.size.x() * Eigen::Vector2d(std::cos(column.yaw), std::sin(column.yaw));
    const Eigen::Vector2d v =
        0.5 * column.size.y() * Eigen::Vector2d(-std::sin(column.yaw), std::cos(column.yaw));
    outline = {column.center - u - v, column.center + u - v, column.center + u + v,
               column.center - u + v};
    return outline;
  }
  const int n = std::max(sides, 3);
  const double reach = column.radius() / std::cos(std::numbers::pi / n);
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * std::numbers::pi * k / n;
    outline.push_back(column.center + reach * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  return outline;
}

}  // namespace isg::bim
