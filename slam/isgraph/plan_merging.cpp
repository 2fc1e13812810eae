#include "slam/isgraph/plan_merging.hpp"

#include <algorithm>
#include <cmath>

#include "bim/optimizer/agraph_factors.hpp"
#include "slam/isgraph/merging_factors.hpp"
#include "slam/isgraph/room_hold.hpp"

namespace isg::slam {

void PlanMerger::addSurface(ceres::Problem& problem, int surface) {
  if (!surfaces_in_problem_.insert(surface).second) return;
  double* block = state_.planes[surface].data();
  problem.AddParameterBlock(block, 4, &plane_manifold_);
  problem.AddResidualBlock(
      bim::PlanePriorFactor::create(bim::toVector(plan_->agraph().surfaces[surface].plane),
                                    options_.plan.plane_angle, options_.plan.plane_distance),
      nullptr, block);
}

std::optional<std::array<double, 2>> PlanMerger::widthsAlongPlanPairs(
    int room, const bim::RoomNode& node, const SGraph& graph, const HeldAnswer& answer) const {
  const auto& s_room = graph.roomCandidates()[room];
  if (!s_room.candidate.four_wall || node.pairs.size() != 2) return std::nullopt;
  const auto& planes = graph.planes();
  const Eigen::Rotation2Dd P_R_M(answer.P_T_M_x_y_yaw.z());
  std::array<double, 2> widths{0.0, 0.0};
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector2d plan_normal =
        plan_->agraph().surfaces[node.pairs[k][0]].plane.normal.head<2>().normalized();
    // The S-room's pair whose normal, turned into P, runs along this plan pair's.
    int along = 0;
    double most = -1.0;
    for (int j = 0; j < 2; ++j) {
      const Eigen::Vector2d n =
          P_R_M * planes[s_room.candidate.pairs[j][0]].parameters.head<2>().normalized();
      if (std::abs(n.dot(plan_normal)) > most) most = std::abs(n.dot(plan_normal)), along = j;
    }
    const auto& pair = s_room.candidate.pairs[along];
    widths[k] = widthThrough(s_room.centre, planes[pair[0]].parameters, planes[pair[1]].parameters);
  }
  return widths;
}

bool PlanMerger::addRoomFactors(ceres::Problem& problem, int room, int plan_room, SGraph& graph,
                                HeldAnswer& answer, const ReleasedWalls& released,
                                std::vector<Eigen::Vector2d>& normals) {
  const bim::RoomNode& node = plan_->agraph().rooms[plan_room];
  // Held along a pair only while that pair's walls stand where the plan has them, as far as
  // the map can tell (holdsAlongPair: room_hold.hpp); along the other pair's normal alone, or
  // not at all, otherwise. Measured in docs/matching.md, "Rooms with a wall built off".
  const auto widths = widthsAlongPlanPairs(room, node, graph, answer);
  std::vector<int> held_pairs;
  for (int k = 0; k < 2; ++k) {
    RoomPairEvidence pair;
    pair.plan_width = node.widths[k];
    pair.map_width = widths ? (*widths)[k] : node.widths[k];
    for (int a : node.pairs[k]) {
      if (const auto offset = released.offsetOf(a)) {
        pair.released_offset = std::max(pair.released_offset, std::abs(*offset));
      }
    }
    if (holdsAlongPair(pair, options_.sigma_room)) held_pairs.push_back(k);
  }
  if (held_pairs.empty()) return false;
  for (const auto& pair : node.pairs) addSurface(problem, pair[0]), addSurface(problem, pair[1]);
  double* centre = state_.rooms[plan_room].data();
  problem.AddResidualBlock(
      bim::FourWallRoomFactor::create(options_.plan.room), nullptr, centre,
      state_.planes[node.pairs[0][0]].data(), state_.planes[node.pairs[0][1]].data(),
      state_.planes[node.pairs[1][0]].data(), state_.planes[node.pairs[1][1]].data());
  if (held_pairs.size() == 2) {
    problem.AddResidualBlock(RoomRoomFactor::create(options_.sigma_room), nullptr,
                             graph.roomCentre(room), answer.P_T_M_x_y_yaw.data(), centre);
    return true;
  }
  const Eigen::Vector2d normal =
      plan_->agraph().surfaces[node.pairs[held_pairs[0]][0]].plane.normal.head<2>().normalized();
  problem.AddResidualBlock(RoomRoomAlongFactor::create(normal, options_.sigma_room), nullptr,
                           graph.roomCentre(room), answer.P_T_M_x_y_yaw.data(), centre);
  normals.push_back(normal);
  return false;
}

void PlanMerger::noteKeyframe(int keyframe, const sensors::Scan& scan,
                              const Eigen::Isometry3d& P_T_R, const Eigen::Isometry3d& R_T_L,
                              int keep_from) {
  sightings_.erase(sightings_.begin(), sightings_.lower_bound(keep_from));
  if (!options_.jambs.enabled) return;
  R_T_L_ = R_T_L;
  std::vector<JambSighting> seen = jambs_.gather(scan.points, P_T_R * R_T_L);
  if (seen.empty()) return;
  sightings_[keyframe] = std::move(seen);
}

void PlanMerger::addJambFactors(ceres::Problem& problem, SGraph& graph, HeldAnswer& answer) {
  for (const auto& [k, seen] : sightings_) {
    if (k >= int(graph.keyframes().size())) continue;
    double* position = graph.keyframePosition(k);
    if (!problem.HasParameterBlock(position) || problem.IsParameterBlockConstant(position)) {
      continue;
    }
    const auto& keyframe = graph.keyframes()[k];
    const Eigen::Isometry3d P_T_L = answer.P_T_M() * keyframe.pose() * R_T_L_;
    for (const JambSighting& sighting : seen) {
      const DoorJamb& jamb = jambs_.jambs()[sighting.jamb];
      // A jamb is kept when its wall is released: a release judges the wall across itself (its
      // offset along its normal, its angle), a jamb holds the map along it. A wall built off
      // its plan across itself leaves its openings where they were along it; built far enough
      // off, its jambs leave their band and are not gathered, and a turn moves them across, out
      // of the band too. On a long floor, the walls most often released are the corridor's own,
      // on the map's bend rather than on the building (docs/matching.md, "Door jambs"): without
      // their jambs, the corridor slid again.
      const auto fit = jambs_.fit(sighting, P_T_L);
      if (!fit) continue;
      const double sigma = std::max(options_.jambs.min_sigma,
                                    options_.jambs.sigma_point / std::sqrt(double(fit->points)));
      problem.AddResidualBlock(
          JambFactor::create(R_T_L_ * fit->centroid_L, jamb.normal, jamb.point, sigma), &huber_,
          position, graph.keyframeOrientation(k), answer.P_T_M_x_y_yaw.data());
      ++jamb_factors_;
    }
  }
}

void PlanMerger::addFactors(ceres::Problem& problem, const std::set<int>& planes,
                            const std::vector<int>& rooms, SGraph& graph, HeldAnswer& answer,
                            const ReleasedWalls& released) {
  if (!answer.localized) return;
  const bim::AGraph& plan = plan_->agraph();
  surfaces_in_problem_.clear();
  // Whether the window's correspondences fix P_T_M: x and y need surface normals in two
  // directions (or a matched four-wall room); yaw any one surface.
  std::vector<Eigen::Vector2d> normals;
  bool room_fixes = false;
  bool any = false;
  for (int p : planes) {
    const auto it = answer.plane_matches.find(p);
    if (it == answer.plane_matches.end()) continue;
    any = true;
    normals.push_back(plan.surfaces[it->second].plane.normal.head<2>().normalized());
    addSurface(problem, it->second);
    problem.AddResidualBlock(
        PlanePlaneFactor::create(options_.sigma_plane_angle, options_.sigma_plane_distance),
        &huber_, graph.planeParameters(p), answer.P_T_M_x_y_yaw.data(),
        state_.planes[it->second].data());
  }
  if (!any) return;
  for (int r : rooms) {
    const auto it = answer.room_matches.find(r);
    if (it == answer.room_matches.end()) continue;
    // A corridor's S-centre lies wherever along it the robot first saw it, not at the plan's
    // centre: only four-wall rooms give a room-to-room factor.
    if (plan.rooms[it->second].kind != bim::RoomKind::kFourWall) continue;
    room_fixes =
        addRoomFactors(problem, r, it->second, graph, answer, released, normals) || room_fixes;
  }
  const double spread = std::sin(options_.min_normal_spread_deg * std::numbers::pi / 180.0);
  bool spans = room_fixes;
  for (std::size_t i = 0; i < normals.size() && !spans; ++i) {
    for (std::size_t j = i + 1; j < normals.size() && !spans; ++j) {
      spans = std::abs(normals[i].x() * normals[j].y() - normals[i].y() * normals[j].x()) >= spread;
    }
  }
  problem.AddResidualBlock(
      PlanarPriorFactor::create(answer.P_T_M_x_y_yaw, options_.sigma_B_T_M_translation,
                                options_.sigma_B_T_M_yaw),
      nullptr, answer.P_T_M_x_y_yaw.data());
  if (!spans) {
    problem.SetParameterBlockConstant(answer.P_T_M_x_y_yaw.data());
    ++held_constant_;
  }
  addJambFactors(problem, graph, answer);
  // The plan's walls between surfaces in the problem.
  for (std::size_t w = 0; w < plan.walls.size(); ++w) {
    const auto& wall = plan.walls[w];
    if (!surfaces_in_problem_.count(wall.left_surface) ||
        !surfaces_in_problem_.count(wall.right_surface)) {
      continue;
    }
    problem.AddResidualBlock(bim::WallFactor::create(wall.anchor, options_.plan.wall), nullptr,
                             state_.walls[w].data(), state_.planes[wall.left_surface].data(),
                             state_.planes[wall.right_surface].data());
  }
}

}  // namespace isg::slam
