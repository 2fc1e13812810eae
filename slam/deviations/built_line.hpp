#pragma once

#include <Eigen/Core>

namespace isg::slam {

// Where a wall stands as built, from its fitted line (docs/deviations.md, "Seen past"): how far
// it lies off its planned axis along the planned left normal at each place along it. A turned
// wall swings off its axis in proportion to the distance from its pivot: 4.4° about a point
// 3.6 m along puts its start 0.27 m off and its middle 0.08 m. The default stands as planned.
struct BuiltLine {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // the planned axis's middle, in B
  Eigen::Vector2d axis = Eigen::Vector2d::UnitX();   // the planned axis's direction (unit)
  double offset_m = 0.0;                             // at the planned middle
  double slope = 0.0;                                // tan of the angle to the planned axis

  Eigen::Vector2d left() const { return {-axis.y(), axis.x()}; }
  // The built line's offset where the normal through `point` meets the planned axis.
  double offsetAt(const Eigen::Vector2d& point) const {
    return offset_m + (point - centre).dot(axis) * slope;
  }
};

}  // namespace isg::slam
