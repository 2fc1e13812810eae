#pragma once

#include <Eigen/Core>
#include <vector>

#include "sim/four_ary_heap.hpp"
#include "sim/occupancy_grid.hpp"

namespace isg::sim {

// A* on one occupancy grid, its per-cell state kept from one search to the next. Why: a level's
// grid has up to OccupancyGrid::kMaxCells cells, and a tour of a large building searches once a
// room; a search that made and filled its cost and parent arrays anew spent most of its time on
// them (a 1000-room floor: 96 MB a search, allocated, zeroed by the kernel and filled), not on the
// cells it visits. A search now resets only the cells it touched. The paths are the same: the
// same costs, the same order of expansion. The open set is a four-ary heap (sim/four_ary_heap.hpp):
// its pops were half of a large floor's searching with std::priority_queue.
class PathSearch {
 public:
  explicit PathSearch(const OccupancyGrid& grid);

  const OccupancyGrid& grid() const { return grid_; }
  // The A* path between two points (cell centres, endpoints included) keeping `min_clearance`
  // from anything blocked, or empty when there is none.
  std::vector<Eigen::Vector2d> find(const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                                    double min_clearance);

 private:
  const OccupancyGrid& grid_;
  std::vector<double> cost_;  // infinity where untouched since the last search
  std::vector<int> parent_;   // -1 where untouched
  std::vector<int> touched_;  // cells whose cost this search set
  FourAryHeap open_;          // the open (f, cell) entries, kept to reuse their memory
};

}  // namespace isg::sim
