#include "slam/baselines/likelihood_field.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "bim/distance_transform.hpp"
#include "bim/plan_geometry.hpp"

namespace isg::slam {

LikelihoodField::LikelihoodField(const bim::Plan& plan, const std::string& level_id,
                                 const LikelihoodFieldOptions& options)
    : cap_(options.max_occupied_distance) {
  const bim::Level* level = plan.findLevel(level_id);
  if (level == nullptr) throw std::invalid_argument("the plan has no level \"" + level_id + "\"");
  if (level->rooms.empty()) {
    throw std::invalid_argument("level \"" + level_id + "\" has no room to localize in");
  }
  const bim::LevelGeometry geometry = bim::computeLevelGeometry(*level);
  Eigen::AlignedBox2d bounds;
  for (const auto& room : level->rooms) {
    for (const auto& p : room.outline) bounds.extend(p);
  }
  for (const auto& wall : geometry.walls) {
    for (const auto& p : wall.footprint()) bounds.extend(p);
  }
  // A margin of one cell keeps every wall inside the grid.
  resolution_ = std::max(options.resolution,
                         std::sqrt(bounds.sizes().prod() / std::max(1.0, options.max_cells)));
  origin_ = bounds.min() - Eigen::Vector2d::Constant(resolution_);
  width_ = int(std::ceil(bounds.sizes().x() / resolution_)) + 2;
  height_ = int(std::ceil(bounds.sizes().y() / resolution_)) + 2;
  const std::size_t cells = std::size_t(width_) * height_;
  std::vector<char> occupied(cells, 0), free(cells, 0);
  const auto centre = [&](int c, int r) {
    return Eigen::Vector2d(origin_ + resolution_ * Eigen::Vector2d(c + 0.5, r + 0.5));
  };
  // A wall occupies the cells whose centre lies in its footprint, at least half a cell thick
  // about its axis so that no wall falls between cell centres, less its door openings.
  for (const auto& wall : geometry.walls) {
    Eigen::AlignedBox2d box;
    for (const auto& p : wall.footprint()) box.extend(p);
    const Eigen::Vector2i lo = ((box.min() - origin_) / resolution_).array().floor().cast<int>();
    const Eigen::Vector2i hi = ((box.max() - origin_) / resolution_).array().ceil().cast<int>();
    const double half_thickness = std::max(0.5 * wall.wall->thickness, 0.5 * resolution_);
    std::vector<bim::AxisInterval> openings;
    for (const auto& door : level->doors) {
      if (door.wall == wall.wall->id) {
        openings.push_back({door.offset - 0.5 * door.width, door.offset + 0.5 * door.width});
      }
    }
    for (int r = std::max(0, lo.y()); r <= std::min(height_ - 1, hi.y()); ++r) {
      for (int c = std::max(0, lo.x()); c <= std::min(width_ - 1, hi.x()); ++c) {
        const Eigen::Vector2d d = centre(c, r) - wall.wall->start;
        const double s = d.dot(wall.axis);
        if (s < -wall.extend_start || s > wall.length + wall.extend_end) continue;
        if (std::abs(d.dot(wall.left_normal)) > half_thickness) continue;
        const bool in_opening = std::any_of(openings.begin(), openings.end(),
                                            [&](const auto& o) { return s > o.lo && s < o.hi; });
        if (!in_opening) occupied[std::size_t(r) * width_ + c] = 1;
      }
    }
  }
  // Round columns: the cells whose centre lies within the circle (at least the nearest one).
  for (const auto& column : level->columns) {
    if (!column.round()) continue;
    const double reach = std::max(column.radius(), 0.5 * resolution_);
    const Eigen::Vector2i lo =
        ((column.center.array() - reach - origin_.array()) / resolution_).floor().cast<int>();
    const Eigen::Vector2i hi =
        ((column.center.array() + reach - origin_.array()) / resolution_).ceil().cast<int>();
    for (int r = std::max(0, lo.y()); r <= std::min(height_ - 1, hi.y()); ++r) {
      for (int c = std::max(0, lo.x()); c <= std::min(width_ - 1, hi.x()); ++c) {
        if ((centre(c, r) - column.center).norm() <= reach)
          occupied[std::size_t(r) * width_ + c] = 1;
      }
    }
  }
  const bim::RoomLocator rooms(*level);
  for (int r = 0; r < height_; ++r) {
    for (int c = 0; c < width_; ++c) {
      const std::size_t i = std::size_t(r) * width_ + c;
      free[i] = !occupied[i] && rooms.roomAt(centre(c, r)).has_value();
    }
  }
  build(occupied, free);
}

LikelihoodField::LikelihoodField(const std::vector<char>& occupied, const std::vector<char>& free,
                                 int width, int height, double resolution,
                                 const Eigen::Vector2d& origin, double max_occupied_distance)
    : resolution_(resolution),
      cap_(max_occupied_distance),
      origin_(origin),
      width_(width),
      height_(height) {
  if (occupied.size() != std::size_t(width) * height || free.size() != occupied.size()) {
    throw std::invalid_argument("the grid's cells do not match its size");
  }
  build(occupied, free);
}

void LikelihoodField::build(const std::vector<char>& occupied, const std::vector<char>& free) {
  occupied_ = occupied;
  free_ = free;
  const std::vector<double> squared = bim::squaredDistanceTransform(occupied, width_, height_);
  distance_.resize(squared.size());
  for (std::size_t i = 0; i < squared.size(); ++i) {
    distance_[i] = float(std::min(cap_, std::sqrt(squared[i]) * resolution_));
  }
  free_cells_.clear();
  for (std::size_t i = 0; i < free.size(); ++i) {
    if (free[i]) free_cells_.push_back(int(i));
  }
}

int LikelihoodField::indexOf(const Eigen::Vector2d& p) const {
  const Eigen::Vector2d q = (p - origin_) / resolution_;
  if (!(q.x() >= 0.0 && q.y() >= 0.0 && q.x() < width_ && q.y() < height_)) return -1;
  return int(q.y()) * width_ + int(q.x());
}

bool LikelihoodField::occupied(const Eigen::Vector2d& p) const {
  const int i = indexOf(p);
  return i >= 0 && occupied_[i];
}

bool LikelihoodField::free(const Eigen::Vector2d& p) const {
  const int i = indexOf(p);
  return i >= 0 && free_[i];
}

}  // namespace isg::slam
