#include "sim/path_search.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <utility>

namespace isg::sim {

PathSearch::PathSearch(const OccupancyGrid& grid)
    : grid_(grid),
      cost_(std::size_t(grid.width()) * std::size_t(grid.height()),
            std::numeric_limits<double>::infinity()),
      parent_(cost_.size(), -1) {}

std::vector<Eigen::Vector2d> PathSearch::find(const Eigen::Vector2d& from,
                                              const Eigen::Vector2d& to, double min_clearance) {
  const OccupancyGrid& grid = grid_;
  const Eigen::Vector2i start = grid.cellOf(from), goal = grid.cellOf(to);
  if (grid.clearance(start) < min_clearance || grid.clearance(goal) < min_clearance) return {};
  const int w = grid.width();
  const auto id = [w](const Eigen::Vector2i& c) { return c.y() * w + c.x(); };
  // What the last search left is undone first: each array holds its untouched value everywhere.
  for (int cell : touched_) {
    cost_[std::size_t(cell)] = std::numeric_limits<double>::infinity();
    parent_[std::size_t(cell)] = -1;
  }
  touched_.clear();
  const auto setCost = [&](int cell, double g) {
    if (std::isinf(cost_[std::size_t(cell)])) touched_.push_back(cell);
    cost_[std::size_t(cell)] = g;
  };
  FourAryHeap& open = open_;
  open.clear();
  const double r = grid.resolution();
  auto heuristic = [&](const Eigen::Vector2i& c) { return r * (c - goal).cast<double>().norm(); };
  setCost(id(start), 0.0);
  open.push({heuristic(start), id(start)});
  static constexpr int kDx[] = {1, -1, 0, 0, 1, 1, -1, -1};
  static constexpr int kDy[] = {0, 0, 1, -1, 1, -1, 1, -1};
  while (!open.empty()) {
    const auto [f, current] = open.top();
    open.pop();
    const Eigen::Vector2i c(current % w, current / w);
    if (c == goal) break;
    if (f - heuristic(c) > cost_[std::size_t(current)] + 1e-9) continue;  // stale entry
    for (int k = 0; k < 8; ++k) {
      const Eigen::Vector2i n(c.x() + kDx[k], c.y() + kDy[k]);
      const double clearance = grid.clearance(n);
      if (clearance < min_clearance) continue;
      // Costlier near walls: paths keep to the middle of rooms and doorways.
      const double step =
          r * (k < 4 ? 1.0 : std::numbers::sqrt2) * (1.0 + 3.0 * std::max(0.0, 1.0 - clearance));
      const double g = cost_[std::size_t(current)] + step;
      if (g < cost_[std::size_t(id(n))]) {
        setCost(id(n), g);
        parent_[std::size_t(id(n))] = current;
        open.push({g + heuristic(n), id(n)});
      }
    }
  }
  if (parent_[std::size_t(id(goal))] < 0 && goal != start) return {};
  std::vector<Eigen::Vector2d> path;
  for (int cell = id(goal); cell != id(start); cell = parent_[std::size_t(cell)]) {
    path.push_back(grid.centreOf({cell % w, cell / w}));
  }
  path.push_back(from);
  std::reverse(path.begin(), path.end());
  path.back() = to;
  return path;
}

}  // namespace isg::sim
