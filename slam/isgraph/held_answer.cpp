#include "slam/isgraph/held_answer.hpp"

#include <string>

#include "common/angles.hpp"

namespace isg::slam {

void HeldAnswer::take(const Verification& answer) {
  P_T_M_x_y_yaw = answer.x_y_yaw;
  plane_matches.clear();
  room_matches.clear();
  for (const auto& [s, a] : answer.planes) plane_matches[s] = a;
  for (const auto& [s, a] : answer.rooms) room_matches[s] = a;
}

void HeldAnswer::clear() {
  localized = false;
  plane_matches.clear();
  room_matches.clear();
}

std::vector<HeldWall> heldWalls(const HeldAnswer& answer, const MatchInput& input,
                                const SGraph& graph, const bim::AGraph& plan,
                                std::vector<std::pair<int, int>>* held) {
  std::map<int, const MatchPlane*> by_id;
  for (const auto& plane : input.planes) by_id[plane.id] = &plane;
  const int floor = graph.currentFloor();
  const Eigen::Rotation2Dd P_R_M(answer.P_T_M_x_y_yaw.z());
  std::vector<HeldWall> walls;
  std::map<std::string, int> walls_by_name;
  for (const auto& [s, a] : answer.plane_matches) {
    const auto plane = by_id.find(s);
    if (plane == by_id.end() || graph.planes()[s].floor != floor) continue;
    const bim::Plane& surface = plan.surfaces[a].plane;
    HeldWall wall;
    wall.middle = answer.inP(0.5 * (plane->second->start + plane->second->end));
    wall.length = plane->second->length();
    wall.normal = surface.normal.head<2>().normalized();
    wall.offset = surface.signedDistance({wall.middle.x(), wall.middle.y(), 0.0});
    wall.angle =
        common::angleDifference(common::headingOf(P_R_M * plane->second->plane.normal.head<2>()),
                                common::headingOf(wall.normal));
    // Plan walls by name; a flight's faces each stand alone.
    const std::string& name = plan.surfaces[a].wall;
    wall.wall = name.empty() ? -1 - a
                             : walls_by_name.emplace(name, int(walls_by_name.size())).first->second;
    walls.push_back(wall);
    if (held) held->emplace_back(s, a);
  }
  return walls;
}

}  // namespace isg::slam
