#include "slam/isgraph/match_input.hpp"

#include <cmath>
#include <map>
#include <set>

namespace isg::slam {

MatchInput matchInputOf(const SGraph& graph, double min_wall_height) {
  MatchInput input;
  const auto& planes = graph.planes();
  const auto& candidates = graph.roomCandidates();
  const int floor = graph.currentFloor();
  std::map<int, int> room_of_keyframe;
  for (int r : graph.confirmedRooms()) {
    const auto& room = candidates[r];
    if (room.floor != floor) continue;
    MatchRoom m;
    m.id = r;
    m.four_wall = room.candidate.four_wall;
    m.centre = room.centre;
    const Eigen::Vector3d& n = planes[room.candidate.pairs[0][0]].map.plane.normal;
    m.axis_yaw = std::atan2(n.y(), n.x());
    m.widths = room.candidate.widths;
    for (int i = 0; i < (m.four_wall ? 2 : 1); ++i) {
      m.planes.push_back(room.candidate.pairs[i][0]);
      m.planes.push_back(room.candidate.pairs[i][1]);
    }
    for (int k : room.keyframes) room_of_keyframe[k] = int(input.rooms.size());
    input.rooms.push_back(m);
  }
  for (int i = 0; i < int(planes.size()); ++i) {
    const auto& p = planes[i];
    // Walls only: clutter seen over a short height is not in the plan.
    if (p.merged_into >= 0 || p.floor != floor || !seenAsWall(p.map, min_wall_height)) {
      continue;
    }
    const Eigen::Vector3d& n = p.map.plane.normal;
    input.planes.push_back({i, p.map.plane, p.map.start, p.map.end, std::atan2(n.y(), n.x())});
  }
  // Consecutive keyframes in two different rooms: the robot walked from one into the other.
  std::set<std::pair<int, int>> transitions;
  for (auto it = room_of_keyframe.begin(); it != room_of_keyframe.end(); ++it) {
    const auto next = room_of_keyframe.find(it->first + 1);
    if (next != room_of_keyframe.end() && next->second != it->second) {
      transitions.insert({std::min(it->second, next->second), std::max(it->second, next->second)});
    }
  }
  input.transitions.assign(transitions.begin(), transitions.end());
  return input;
}

namespace {

// The index of the first of the latest `keyframes` keyframes of `graph`.
std::size_t firstOfLatest(const SGraph& graph, int keyframes) {
  const std::size_t all = graph.keyframes().size();
  return all > std::size_t(keyframes) ? all - std::size_t(keyframes) : 0;
}

}  // namespace

MatchInput recentPlanesOf(const MatchInput& input, const SGraph& graph, int keyframes) {
  const auto& all = graph.keyframes();
  std::set<int> recent;
  for (std::size_t i = firstOfLatest(graph, keyframes); i < all.size(); ++i) {
    for (const auto& [plane, observation] : all[i].observations) recent.insert(plane);
  }
  MatchInput local;
  for (const MatchPlane& plane : input.planes) {
    if (recent.count(plane.id)) local.planes.push_back(plane);
  }
  return local;
}

MatchInput recentStretchesOf(const MatchInput& input, const SGraph& graph,
                             const Eigen::Isometry3d& R_T_L, int keyframes) {
  std::map<int, const MatchPlane*> by_id;
  for (const MatchPlane& plane : input.planes) by_id[plane.id] = &plane;
  std::map<int, std::pair<double, double>> stretch;  // plane → [lo, hi] along it
  const auto& all = graph.keyframes();
  for (std::size_t k = firstOfLatest(graph, keyframes); k < all.size(); ++k) {
    const Eigen::Isometry3d M_T_L = all[k].pose() * R_T_L;
    for (const auto& [plane, observation] : all[k].observations) {
      const auto it = by_id.find(plane);
      if (it == by_id.end()) continue;
      const Eigen::Vector2d along = alongWall(it->second->plane);
      const double a = along.dot((M_T_L * observation.start).head<2>());
      const double b = along.dot((M_T_L * observation.end).head<2>());
      auto [entry, added] = stretch.try_emplace(plane, std::min(a, b), std::max(a, b));
      if (!added) {
        entry->second.first = std::min({entry->second.first, a, b});
        entry->second.second = std::max({entry->second.second, a, b});
      }
    }
  }
  MatchInput local;
  for (const auto& [plane, range] : stretch) {
    MatchPlane cut = *by_id.at(plane);
    const Eigen::Vector2d along = alongWall(cut.plane);
    const Eigen::Vector2d n = cut.plane.normal.head<2>();
    // The point of the plane's horizontal line nearest M's origin, then along it.
    const Eigen::Vector2d origin = -cut.plane.d * n / n.squaredNorm();
    cut.start = origin + (range.first - along.dot(origin)) * along;
    cut.end = origin + (range.second - along.dot(origin)) * along;
    local.planes.push_back(cut);
  }
  return local;
}

MatchInput recentSightingsOf(const SGraph& graph, const Eigen::Isometry3d& R_T_L, int keyframes,
                             double min_wall_height) {
  const auto& all = graph.keyframes();
  const auto& planes = graph.planes();
  const int floor = graph.currentFloor();
  std::map<int, MatchPlane> newest;  // by the wall's plane index
  for (std::size_t k = firstOfLatest(graph, keyframes); k < all.size(); ++k) {
    const auto& keyframe = all[k];
    if (!keyframe.onFloor() || keyframe.floor != floor) continue;
    const Eigen::Isometry3d M_T_L = keyframe.pose() * R_T_L;
    for (const auto& [seen, observation] : keyframe.observations) {
      int plane = seen;
      while (planes[plane].merged_into >= 0) plane = planes[plane].merged_into;
      if (planes[plane].floor != floor || !seenAsWall(planes[plane].map, min_wall_height)) {
        continue;
      }
      MatchPlane m;
      m.id = plane;
      m.plane = observation.plane.transformed(M_T_L);
      m.start = (M_T_L * observation.start).head<2>();
      m.end = (M_T_L * observation.end).head<2>();
      m.normal_yaw = std::atan2(m.plane.normal.y(), m.plane.normal.x());
      newest[plane] = m;  // later keyframes replace earlier sightings
    }
  }
  MatchInput input;
  for (const auto& [plane, m] : newest) input.planes.push_back(m);
  return input;
}

}  // namespace isg::slam
