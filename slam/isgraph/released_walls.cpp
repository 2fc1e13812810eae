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
    log_.push_back({stamp, s, a, residuals[k].offset, residuals[k].angle});
    planes_.insert(s);
    surfaces_[a] = residuals[k].offset;
    plane_matches.erase(s);
    strikes_.erase(s);
  }
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
    }
  }
  for (const MatchPlane& plane : planes) strikes_.erase(plane.id);
}

void ReleasedWalls::clear() {
  log_.clear();
  planes_.clear();
  surfaces_.clear();
  strikes_.clear();
}

}  // namespace isg::slam
