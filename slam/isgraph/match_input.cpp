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

}  // namespace isg::slam
