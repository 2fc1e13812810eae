#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace isg::bim {

// An axis-aligned box in the plane.
struct Box2 {
  Eigen::Vector2d lo = Eigen::Vector2d::Zero();
  Eigen::Vector2d hi = Eigen::Vector2d::Zero();

  static Box2 around(const Eigen::Vector2d& a, const Eigen::Vector2d& b);
  static Box2 around(const std::vector<Eigen::Vector2d>& points);
  Box2 grown(double margin) const;
  bool overlaps(const Box2& other) const;
  bool contains(const Eigen::Vector2d& point) const;
};

// A uniform grid over item boxes that answers "which items may overlap this box" in time
// proportional to the answer, so that pairwise geometry checks (self-intersecting outlines,
// wall junctions, faces on walls) stay near-linear instead of quadratic. The cell size follows
// the items' median size; an item that would cover more than kMaxCellsPerItem cells is kept in a
// short list that every query returns, so one very long wall cannot blow the grid up.
class BoxGrid {
 public:
  explicit BoxGrid(std::vector<Box2> boxes);

  // Every item whose box overlaps `query` (and possibly a few that only share a cell with it),
  // each once, in increasing index order.
  std::vector<int> candidates(const Box2& query) const;
  const Box2& box(int item) const { return boxes_[std::size_t(item)]; }
  int size() const { return int(boxes_.size()); }

  static constexpr std::int64_t kMaxCellsPerItem = 64;

 private:
  Eigen::Vector2i cellOf(const Eigen::Vector2d& p) const;

  std::vector<Box2> boxes_;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double cell_ = 1.0;
  Eigen::Vector2i cells_ = Eigen::Vector2i::Ones();
  std::vector<std::vector<int>> buckets_;
  std::vector<int> oversized_;
  mutable std::vector<std::uint32_t> seen_;  // query stamps, to report each item once
  mutable std::uint32_t stamp_ = 0;
};

}  // namespace isg::bim
