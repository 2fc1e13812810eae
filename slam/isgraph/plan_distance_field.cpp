#include "slam/isgraph/plan_distance_field.hpp"

#include <algorithm>
#include <cmath>

#include "bim/polygon.hpp"

namespace isg::slam {

PlanDistanceField::PlanDistanceField(const bim::AGraph& plan, double cap) : cap_(cap) {
  const Eigen::AlignedBox2d bounds = plan.surfaceBounds();
  if (bounds.isEmpty()) return;  // no surfaces: every distance is the cap
  origin_ = bounds.min() - Eigen::Vector2d::Constant(cap);
  const Eigen::Vector2d extent = bounds.sizes() + Eigen::Vector2d::Constant(2.0 * cap);
  constexpr double kMaxCells = 4e6;
  resolution_ = std::max(0.1, std::sqrt(extent.x() * extent.y() / kMaxCells));
  columns_ = int(std::ceil(extent.x() / resolution_)) + 1;
  rows_ = int(std::ceil(extent.y() / resolution_)) + 1;
  cells_.assign(std::size_t(columns_) * rows_, float(cap));
  // Each segment updates the cells within the cap of it.
  for (const auto& surface : plan.surfaces) {
    for (const auto& [a, b] : surface.segments) {
      const Eigen::Vector2d box_lo = a.cwiseMin(b) - Eigen::Vector2d::Constant(cap) - origin_;
      const Eigen::Vector2d box_hi = a.cwiseMax(b) + Eigen::Vector2d::Constant(cap) - origin_;
      const int c0 = std::max(0, int(box_lo.x() / resolution_));
      const int c1 = std::min(columns_ - 1, int(box_hi.x() / resolution_) + 1);
      const int r0 = std::max(0, int(box_lo.y() / resolution_));
      const int r1 = std::min(rows_ - 1, int(box_hi.y() / resolution_) + 1);
      for (int r = r0; r <= r1; ++r) {
        for (int c = c0; c <= c1; ++c) {
          const Eigen::Vector2d centre = origin_ + resolution_ * Eigen::Vector2d(c + 0.5, r + 0.5);
          float& cell = cells_[std::size_t(r) * columns_ + c];
          cell = std::min(cell, float(bim::distanceToSegment(centre, a, b)));
        }
      }
    }
  }
}

double PlanDistanceField::distance(const Eigen::Vector2d& p) const {
  if (cells_.empty()) return cap_;
  const Eigen::Vector2d q = (p - origin_) / resolution_;
  if (!(q.x() >= 0.0 && q.y() >= 0.0 && q.x() < columns_ && q.y() < rows_)) return cap_;
  return cells_[std::size_t(q.y()) * columns_ + std::size_t(q.x())];
}

}  // namespace isg::slam
