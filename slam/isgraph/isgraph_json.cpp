#include "slam/isgraph/isgraph_json.hpp"

#include <string>

#include "common/angles.hpp"

namespace isg::slam {

namespace {

// The answer held: B_T_M, the level of the floor stood on, and each floor's level.
void addAnswer(const ISGraphView& view, nlohmann::json& matching) {
  const bim::AGraph& plan = view.plan.agraph();
  const Eigen::Vector3d B_T_M = view.plan.inB(view.answer.P_T_M_x_y_yaw);
  matching["B_T_M"] = {
      {"x", B_T_M.x()}, {"y", B_T_M.y()}, {"z", view.answer.P_T_M_z}, {"yaw", B_T_M.z()}};
  const int level = view.floors.level();
  if (level >= 0 && level < int(plan.floors.size())) matching["level"] = plan.floors[level].id;
  nlohmann::json floor_levels = nlohmann::json::object();
  for (const auto& [floor, floor_level] : view.floors.floorLevels()) {
    floor_levels[std::to_string(floor)] = plan.floors[floor_level].id;
  }
  matching["floor_levels"] = floor_levels;
}

}  // namespace

nlohmann::json matchingJson(const ISGraphView& view) {
  const bim::AGraph& plan = view.plan.agraph();
  nlohmann::json planes = nlohmann::json::array(), rooms = nlohmann::json::array();
  for (const auto& [s, a] : view.answer.plane_matches) planes.push_back({s, plan.surfaces[a].id});
  for (const auto& [s, a] : view.answer.room_matches) rooms.push_back({s, plan.rooms[a].id});
  nlohmann::json released = nlohmann::json::array();
  for (const auto& r : view.released.log()) {
    released.push_back({{"stamp", r.stamp},
                        {"plane", r.plane},
                        {"surface", plan.surfaces[r.surface].id},
                        {"offset_m", r.offset},
                        {"angle_deg", common::degrees(r.angle)}});
  }
  nlohmann::json matching = {{"localized", view.answer.localized},
                             {"windows_with_B_T_M_held", view.windows_with_answer_held},
                             {"jamb_factors", view.jamb_factors},
                             {"map_bends", view.map_bends},
                             {"plane_matches", planes},
                             {"released_walls", released},
                             {"room_matches", rooms}};
  view.log.addTo(matching);
  if (view.answer.localized) addAnswer(view, matching);
  nlohmann::json level_changes = nlohmann::json::array();
  for (const auto& change : view.floors.changes()) {
    level_changes.push_back({{"stamp", change.stamp},
                             {"floor", change.floor},
                             {"level", plan.floors[change.level].id}});
  }
  if (!level_changes.empty()) matching["level_changes"] = level_changes;
  return matching;
}

}  // namespace isg::slam
