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

MatchInput recentPlanesOf(const MatchInput& input, const SGraph& graph, int keyframes) {
  const auto& all = graph.keyframes();
  std::set<int> recent;
  const std::size_t first =
      all.size() > std::size_t(keyframes) ? all.size() - std::size_t(keyframes) : 0;
  for (std::size_t i = first; i < all.size(); ++i) {
    for (const auto& [plane, observation] : all[i].observations) recent.insert(plane);
  }
  MatchInput local;
  for (const MatchPlane& plane : input.planes) {
    if (recent.count(plane.id)) local.planes.push_back(plane);
  }
  return local;
}

MatchInput recentSightingsOf(const SGraph& graph, const Eigen::Isometry3d& R_T_L, int keyframes,
                             double min_wall_height) {
  const auto& all = graph.keyframes();
  const auto& planes = graph.planes();
  const int floor = graph.currentFloor();
  const std::size_t first =
      all.size() > std::size_t(keyframes) ? all.size() - std::size_t(keyframes) : 0;
  std::map<int, MatchPlane> newest;  // by the wall's plane index
  for (std::size_t k = first; k < all.size(); ++k) {
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
