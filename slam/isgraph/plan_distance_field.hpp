#pragma once

#include <Eigen/Core>
#include <vector>

#include "bim/agraph.hpp"

namespace isg::slam {

// Distance from any point of the plan frame B (x, y) to the nearest exposed wall surface of the
// plan, capped: a grid over the plan's extent (docs/matching.md). What "does this scan agree with
// the plan here?" is asked of. The cell is 0.1 m, coarser for plans so large that the grid would
// exceed 4 million cells.
class PlanDistanceField {
 public:
  explicit PlanDistanceField(const bim::AGraph& plan, double cap = 1.0);

  // Distance to the nearest surface, at most `cap` (also outside the grid).
  double distance(const Eigen::Vector2d& p) const;
  double resolution() const { return resolution_; }

 private:
  double cap_;
  double resolution_ = 0.1;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  int columns_ = 0, rows_ = 0;
  std::vector<float> cells_;
};

}  // namespace isg::slam
