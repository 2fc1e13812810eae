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

  // At most this many cells: a larger level gets coarser cells than asked for. Why this many: a
  // doorway of 0.9 m leaves a robot keeping 0.35 m from walls 0.1 m of play, and the clearance
  // bound loses about 1.7 cells of it (a cell diagonal subtracted, and the nearest blocked cell
  // centre up to half a cell off the true jamb), so cells much over 6 cm shut such doorways: an
  // L of 1000 offices (174 × 169 m, 11.8 M cells of 5 cm) shut 167 of them at 8 M cells (6.1 cm).
  // 2.4e7 keeps 5 cm cells to a box of 60 000 m² (245 × 245 m), at about 17 bytes a cell for the
  // grid and the path search (about 410 MB at most).
  static constexpr double kMaxCells = 2.4e7;

  int width() const { return width_; }
  int height() const { return height_; }
  double resolution() const { return resolution_; }
  // The cell size asked for; resolution() is larger when the level is past kMaxCells such cells.
  double askedResolution() const { return asked_resolution_; }

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
  double asked_resolution_;
  Eigen::Vector2d origin_;  // xy of cell (0, 0)'s corner
  int width_ = 0;
  int height_ = 0;
  std::vector<char> blocked_;
  std::vector<float> clearance_;
};

}  // namespace isg::sim
