#include "slam/deviations/plan_segment_grid.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "bim/polygon.hpp"

namespace isg::slam {

PlanSegmentGrid::PlanSegmentGrid(const bim::AGraph& plan, double cutoff, double margin) {
  const Eigen::AlignedBox2d bounds = plan.surfaceBounds();
  if (bounds.isEmpty()) return;
  origin_ = bounds.min() - Eigen::Vector2d::Constant(cutoff + kCell);
  columns_ = int(std::ceil((bounds.sizes().x() + 2 * (cutoff + kCell)) / kCell)) + 1;
  rows_ = int(std::ceil((bounds.sizes().y() + 2 * (cutoff + kCell)) / kCell)) + 1;
  cells_.resize(std::size_t(columns_) * rows_);
  for (int s = 0; s < int(plan.surfaces.size()); ++s) {
    const bim::WallSurfaceNode& surface = plan.surfaces[s];
    const double lo = surface.z_min + margin, hi = surface.z_max - margin;
    if (!(lo < hi)) continue;
    bands_.push_back({lo, hi});
    for (const auto& [a, b] : surface.segments) {
      const int index = int(segments_.size());
      segments_.push_back({a, b, lo, hi, s});
      const Eigen::Vector2d box_lo = a.cwiseMin(b) - Eigen::Vector2d::Constant(cutoff) - origin_;
      const Eigen::Vector2d box_hi = a.cwiseMax(b) + Eigen::Vector2d::Constant(cutoff) - origin_;
      for (int r = int(box_lo.y() / kCell); r <= int(box_hi.y() / kCell); ++r) {
        for (int c = int(box_lo.x() / kCell); c <= int(box_hi.x() / kCell); ++c) {
          cells_[std::size_t(r) * columns_ + c].push_back(index);
        }
      }
    }
  }
}

bool PlanSegmentGrid::inBand(double z) const {
  return std::any_of(bands_.begin(), bands_.end(),
                     [&](const auto& band) { return z >= band[0] && z <= band[1]; });
}

std::optional<PlanSegmentGrid::Nearest> PlanSegmentGrid::nearest(const Eigen::Vector3d& p) const {
  const Eigen::Vector2d q = (p.head<2>() - origin_) / kCell;
  if (!(q.x() >= 0 && q.y() >= 0 && q.x() < columns_ && q.y() < rows_)) return std::nullopt;
  std::optional<Nearest> best;
  for (int index : cells_[std::size_t(q.y()) * columns_ + std::size_t(q.x())]) {
    const Segment& s = segments_[std::size_t(index)];
    if (p.z() < s.z_lo || p.z() > s.z_hi) continue;
    const double d = bim::distanceToSegment(p.head<2>(), s.a, s.b);
    if (!best || d < best->distance) best = Nearest{d, index};
  }
  return best;
}

}  // namespace isg::slam
