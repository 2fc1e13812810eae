#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "bim/plan.hpp"

namespace isg::slam {

// The map AMCL localizes in: an occupancy grid rasterised from the plan (not the building as
// built: the plan is all a real robot has), with ROS AMCL's likelihood field — every cell's
// distance to the nearest occupied cell, capped (laser_likelihood_max_dist).
struct LikelihoodFieldOptions {
  double resolution = 0.05;            // metres per cell, as a map_server map
  double max_occupied_distance = 2.0;  // nav2's laser_likelihood_max_dist
  // At most this many cells: a larger level gets coarser cells than asked for.
  double max_cells = 2.5e7;
};

class LikelihoodField {
 public:
  // Occupied: the level's wall footprints with the door openings cut out (a plan's doors are
  // openings). Free: cells inside a room outline that are not occupied. Throws
  // std::invalid_argument when the level does not exist or has no room.
  LikelihoodField(const bim::Plan& plan, const std::string& level,
                  const LikelihoodFieldOptions& options = {});
  // A grid given cell by cell (row-major, width × height, cell (0, 0)'s corner at `origin`).
  LikelihoodField(const std::vector<char>& occupied, const std::vector<char>& free, int width,
                  int height, double resolution, const Eigen::Vector2d& origin,
                  double max_occupied_distance);

  // Distance from the cell holding p to the nearest occupied cell (centre to centre), at most
  // the cap; the cap outside the grid (as AMCL's map).
  double distance(const Eigen::Vector2d& p) const {
    const Eigen::Vector2d q = (p - origin_) / resolution_;
    if (!(q.x() >= 0.0 && q.y() >= 0.0 && q.x() < width_ && q.y() < height_)) return cap_;
    return distance_[std::size_t(q.y()) * width_ + std::size_t(q.x())];
  }
  bool occupied(const Eigen::Vector2d& p) const;
  bool free(const Eigen::Vector2d& p) const;
  // The free cells' indices (row-major), for uniform draws over the free space.
  const std::vector<int>& freeCells() const { return free_cells_; }
  Eigen::Vector2d cellCorner(int index) const {
    return origin_ + resolution_ * Eigen::Vector2d(index % width_, index / width_);
  }
  double resolution() const { return resolution_; }
  double cap() const { return cap_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  void build(const std::vector<char>& occupied, const std::vector<char>& free);
  int indexOf(const Eigen::Vector2d& p) const;

  double resolution_ = 0.05;
  double cap_ = 2.0;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  int width_ = 0, height_ = 0;
  std::vector<char> occupied_, free_;
  std::vector<float> distance_;
  std::vector<int> free_cells_;
};

}  // namespace isg::slam
