#include "slam/isgraph/released_walls.hpp"

#include <algorithm>

namespace isg::slam {

void ReleasedWalls::judge(const std::vector<HeldWall>& walls,
                          const std::vector<std::pair<int, int>>& held, double stamp,
                          int strikes_needed, std::map<int, int>& plane_matches) {
  const std::vector<WallResidual> residuals = residualsAgainstOthers(walls, options_);
  int judged = 0;
  std::vector<std::size_t> due;
  // Strikes count keyframes in a row: a plane not judged beyond now (within, or not judged at all,
  // as when it is on another floor) starts again from none.
  std::map<int, int> strikes;
  for (std::size_t k = 0; k < residuals.size(); ++k) {
    judged += residuals[k].judged ? 1 : 0;
    if (!residuals[k].beyond(options_)) continue;
    const int s = held[k].first;
    const auto before = strikes_.find(s);
    strikes[s] = 1 + (before == strikes_.end() ? 0 : before->second);
    if (strikes[s] >= strikes_needed) due.push_back(k);
  }
  strikes_ = std::move(strikes);
  if (2 * int(due.size()) > judged) return;
  for (std::size_t k : due) {
    const auto [s, a] = held[k];
    const HeldWall& wall = walls[k];
    const Eigen::Vector2d half =
        0.5 * wall.length * Eigen::Vector2d(-wall.normal.y(), wall.normal.x());
    const Release release{stamp,
                          s,
                          a,
                          residuals[k].offset,
                          residuals[k].angle,
                          wall.middle - half,
                          wall.middle + half};
    log_.push_back(release);
    planes_.insert(s);
    surfaces_[a] = residuals[k].offset;
    stretches_.emplace(a, release);
    plane_matches.erase(s);
    strikes_.erase(s);
  }
}

bool ReleasedWalls::allows(int plane, int surface, const Eigen::Vector2d& start_in_P,
                           const Eigen::Vector2d& end_in_P) const {
  if (planes_.count(plane)) return false;
  const auto [first, last] = stretches_.equal_range(surface);
  for (auto it = first; it != last; ++it) {
    const Release& r = it->second;
    // Along the released stretch (its surface's direction), the two segments' intervals.
    const Eigen::Vector2d along = r.end - r.start;
    const double length = along.norm();
    const Eigen::Vector2d unit =
        length > 1e-9 ? Eigen::Vector2d(along / length) : Eigen::Vector2d(Eigen::Vector2d::UnitX());
    const double a = unit.dot(start_in_P - r.start), b = unit.dot(end_in_P - r.start);
    const double margin = options_.stretch_margin;
    if (std::max(a, b) >= -margin && std::min(a, b) <= length + margin) return false;
  }
  return true;
}

std::optional<double> ReleasedWalls::offsetOf(int surface) const {
  const auto it = surfaces_.find(surface);
  if (it == surfaces_.end()) return std::nullopt;
  return it->second;
}

void ReleasedWalls::reopen(const std::vector<MatchPlane>& planes) {
  for (const Release& r : log_) {
    if (std::any_of(planes.begin(), planes.end(),
                    [&](const MatchPlane& p) { return p.id == r.plane; })) {
      planes_.erase(r.plane);
      surfaces_.erase(r.surface);
      std::erase_if(stretches_, [&](const auto& entry) { return entry.second.plane == r.plane; });
    }
  }
  for (const MatchPlane& plane : planes) strikes_.erase(plane.id);
}

void ReleasedWalls::clear() {
  log_.clear();
  planes_.clear();
  surfaces_.clear();
  stretches_.clear();
  strikes_.clear();
}

}  // namespace isg::slam
