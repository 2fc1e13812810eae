#include "bim/box_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace isg::bim {

namespace {

// Cells per axis are capped so that the grid never holds more than a few cells per item.
constexpr double kCellsPerItem = 4.0;

}  // namespace

Box2 Box2::around(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return {a.cwiseMin(b), a.cwiseMax(b)};
}

Box2 Box2::around(const std::vector<Eigen::Vector2d>& points) {
  Box2 box{Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()),
           Eigen::Vector2d::Constant(-std::numeric_limits<double>::infinity())};
  for (const auto& p : points) {
    box.lo = box.lo.cwiseMin(p);
    box.hi = box.hi.cwiseMax(p);
  }
  return box;
}

Box2 Box2::grown(double margin) const {
  return {lo - Eigen::Vector2d::Constant(margin), hi + Eigen::Vector2d::Constant(margin)};
}

bool Box2::overlaps(const Box2& other) const {
  return lo.x() <= other.hi.x() && other.lo.x() <= hi.x() && lo.y() <= other.hi.y() &&
         other.lo.y() <= hi.y();
}

bool Box2::contains(const Eigen::Vector2d& point) const {
  return (point.array() >= lo.array()).all() && (point.array() <= hi.array()).all();
}

BoxGrid::BoxGrid(std::vector<Box2> boxes) : boxes_(std::move(boxes)), seen_(boxes_.size(), 0) {
  if (boxes_.empty()) return;
  Box2 all = boxes_.front();
  std::vector<double> sizes;
  sizes.reserve(boxes_.size());
  for (const auto& b : boxes_) {
    all.lo = all.lo.cwiseMin(b.lo);
    all.hi = all.hi.cwiseMax(b.hi);
    sizes.push_back(std::max(b.hi.x() - b.lo.x(), b.hi.y() - b.lo.y()));
  }
  std::nth_element(sizes.begin(), sizes.begin() + std::ptrdiff_t(sizes.size() / 2), sizes.end());
  const Eigen::Vector2d extent = (all.hi - all.lo).cwiseMax(1e-9);
  // The median item spans about one cell; no more cells than kCellsPerItem per item overall.
  const double min_cell = std::sqrt(extent.x() * extent.y() / (kCellsPerItem * boxes_.size()));
  cell_ = std::max({sizes[sizes.size() / 2], min_cell, 1e-9 * extent.maxCoeff()});
  origin_ = all.lo;
  // A flat extent (all items in a row) would make many empty cells: coarsen until it fits.
  const double max_cells = kCellsPerItem * double(boxes_.size()) + 16.0;
  Eigen::Vector2d counts = (extent / cell_).array().floor() + 1.0;
  while (counts.x() * counts.y() > max_cells) {
    cell_ *= 2.0;
    counts = (extent / cell_).array().floor() + 1.0;
  }
  cells_ = counts.cast<int>();
  buckets_.resize(std::size_t(cells_.x()) * std::size_t(cells_.y()));
  for (int i = 0; i < int(boxes_.size()); ++i) {
    const Eigen::Vector2i a = cellOf(boxes_[std::size_t(i)].lo);
    const Eigen::Vector2i b = cellOf(boxes_[std::size_t(i)].hi);
    const std::int64_t covered = std::int64_t(b.x() - a.x() + 1) * (b.y() - a.y() + 1);
    if (covered > kMaxCellsPerItem) {
      oversized_.push_back(i);
      continue;
    }
    for (int y = a.y(); y <= b.y(); ++y) {
      for (int x = a.x(); x <= b.x(); ++x) {
        buckets_[std::size_t(y) * std::size_t(cells_.x()) + std::size_t(x)].push_back(i);
      }
    }
  }
}

Eigen::Vector2i BoxGrid::cellOf(const Eigen::Vector2d& p) const {
  const Eigen::Vector2d q = ((p - origin_) / cell_).array().floor();
  return {int(std::clamp(q.x(), 0.0, double(cells_.x() - 1))),
          int(std::clamp(q.y(), 0.0, double(cells_.y() - 1)))};
}

std::vector<int> BoxGrid::candidates(const Box2& query) const {
  std::vector<int> out;
  if (boxes_.empty()) return out;
  if (++stamp_ == 0) {  // wrapped: forget every old stamp
    std::fill(seen_.begin(), seen_.end(), 0);
    stamp_ = 1;
  }
  auto take = [&](int i) {
    if (seen_[std::size_t(i)] == stamp_) return;
    seen_[std::size_t(i)] = stamp_;
    if (boxes_[std::size_t(i)].overlaps(query)) out.push_back(i);
  };
  for (int i : oversized_) take(i);
  const Eigen::Vector2i a = cellOf(query.lo);
  const Eigen::Vector2i b = cellOf(query.hi);
  for (int y = a.y(); y <= b.y(); ++y) {
    for (int x = a.x(); x <= b.x(); ++x) {
      for (int i : buckets_[std::size_t(y) * std::size_t(cells_.x()) + std::size_t(x)]) take(i);
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace isg::bim
