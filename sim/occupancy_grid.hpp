#pragma once

#include <Eigen/Core>
#include <vector>

#include "bim/plan.hpp"
#include "bim/plan_geometry.hpp"
#include "bim/scenario.hpp"

namespace isg::sim {

// Where the robot's centre may go on one level of the building as built: inside rooms and through
// open doorways between rooms, away from walls, clutter and closed doors. Doors to the outside are
// kept shut: a tour stays in the building. Each free cell knows its clearance (distance to the
// nearest blocked cell), from an exact Euclidean distance transform.
class OccupancyGrid {
 public:
  OccupancyGrid(const bim::Plan& plan, const bim::AsBuilt& as_built, const std::string& level,
                double resolution = 0.05);

  // At most this many cells: a larger level gets coarser cells than asked for.
  static constexpr double kMaxCells = 8e6;

  int width() const { return width_; }
  int height() const { return height_; }
  double resolution() const { return resolution_; }

  Eigen::Vector2i cellOf(const Eigen::Vector2d& p) const;
  Eigen::Vector2d centreOf(const Eigen::Vector2i& c) const;
  bool inside(const Eigen::Vector2i& c) const {
    return c.x() >= 0 && c.y() >= 0 && c.x() < width_ && c.y() < height_;
  }
  bool blocked(const Eigen::Vector2i& c) const { return !inside(c) || blocked_[index(c)]; }
  // A lower bound, in metres, of the distance from any point of the cell to the nearest wall,
  // clutter or closed door (0 for blocked cells).
  double clearance(const Eigen::Vector2i& c) const {
    return inside(c) ? clearance_[index(c)] : 0.0;
  }
  double clearanceAt(const Eigen::Vector2d& p) const { return clearance(cellOf(p)); }

 private:
  int index(const Eigen::Vector2i& c) const { return c.y() * width_ + c.x(); }
  // Sets every cell whose centre bim::containsPoint puts inside `polygon`.
  void paint(const std::vector<Eigen::Vector2d>& polygon, bool blocked);
  // The grid's origin, size and resolution over the level's walls and rooms, every cell blocked.
  void frame(const bim::Level& level, const bim::LevelGeometry& geometry, double resolution);
  // The planned footprints of walls missing, shifted or turned as built painted as floor.
  void clearPlannedWalls(const bim::Level& plan_level, const bim::AsBuilt& as_built);
  // The flights of stairs that start or end on the level blocked (their steps, or the stairwell).
  void paintFlights(const bim::Plan& plan, const bim::Level& plan_level);

  double resolution_;
  Eigen::Vector2d origin_;  // xy of cell (0, 0)'s corner
  int width_ = 0;
  int height_ = 0;
  std::vector<char> blocked_;
  std::vector<float> clearance_;
};

}  // namespace isg::sim
