#include "slam/isgraph/plan_agreement.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>
#include <vector>

namespace isg::slam {

double PlanAgreement::planShare(const SGraph& graph, const HeldAnswer& answer) const {
  const auto& keyframe = graph.keyframes().back();
  if (keyframe.cloud.empty()) return -1.0;
  const Eigen::Isometry3d M_T_L = keyframe.pose() * R_T_L_;
  const double sensor_z = M_T_L.translation().z();
  int used = 0, near = 0;
  for (const auto& p : keyframe.cloud) {
    const Eigen::Vector3d q = M_T_L * p.cast<double>();
    if (q.z() < sensor_z - 0.4 || q.z() > sensor_z + 1.2) continue;  // floor, ceiling
    ++used;
    if (plan_->distanceField().distance(answer.inP(q.head<2>())) <= options_.plan_share_distance)
      ++near;
  }
  return used > 0 ? double(near) / used : -1.0;
}

void PlanAgreement::clear() {
  plan_shares_.clear();
  plan_collapsed_ = 0;
  dropped_disagreeing_ = 0;
  unconfirmed_.clear();
}

std::string PlanAgreement::scanDisagreement(const SGraph& graph, const HeldAnswer& answer) {
  const double plan_share = planShare(graph, answer);
  if (plan_share < 0.0) return "";
  const auto& keyframe = graph.keyframes().back();
  char text[256];
  std::vector<double> recent(plan_shares_.begin(), plan_shares_.end());
  double median = -1.0;
  if (recent.size() >= 3) {
    std::nth_element(recent.begin(), recent.begin() + recent.size() / 2, recent.end());
    median = recent[recent.size() / 2];
  }
  // On the stairs the view turns from one floor to the next through the stairwell: a scan
  // unlike the recent map is expected there.
  const bool map_disagrees = keyframe.onFloor() && keyframe.registration.attempted &&
                             keyframe.registration.inlier_share < options_.suspect_share;
  // Without a history of plan shares yet (just localized), a scan that does not agree with
  // the recent map at all is enough.
  const bool plan_disagrees =
      median > 0.0 ? plan_share < options_.plan_share_drop * median
                   : keyframe.registration.attempted && !keyframe.registration.agrees;
  if (map_disagrees && plan_disagrees) {
    std::snprintf(text, sizeof text,
                  "the scan agrees neither with the recent map (%.0f %% of its points near it) "
                  "nor with the plan (%.0f %% of its wall points on a plan wall, %.0f %% before)",
                  100.0 * keyframe.registration.inlier_share, 100.0 * plan_share, 100.0 * median);
    return text;
  }
  plan_collapsed_ =
      median > 0.0 && plan_share < options_.plan_share_collapse * median ? plan_collapsed_ + 1 : 0;
  if (plan_collapsed_ >= 2) {
    std::snprintf(text, sizeof text,
                  "the scans no longer agree with the plan (%.0f %% of the wall points on a plan "
                  "wall, %.0f %% before)",
                  100.0 * plan_share, 100.0 * median);
    // A loss even when the scan still agrees with the recent map: a kidnap to a place that looks
    // like the last one registers on it (the kidnap suite's D5, seed 2), and only the plan tells.
    return text;
  }
  plan_shares_.push_back(plan_share);
  while (int(plan_shares_.size()) > options_.plan_share_history) plan_shares_.pop_front();
  return "";
}

std::string PlanAgreement::heldDisagreement(const MatchInput& input, const SGraph& graph,
                                            HeldAnswer& answer) {
  // Held correspondences: those that left the hold gate are dropped; if most of the ones the
  // latest keyframe sees left it, the plan contradicts what the robot sees now.
  std::map<int, const MatchPlane*> by_id;
  for (const auto& plane : input.planes) by_id[plane.id] = &plane;
  std::set<int> seen_now;
  for (const auto& [plane, observation] : graph.keyframes().back().observations) {
    seen_now.insert(plane);
  }
  int seen_matched = 0, seen_disagreeing = 0;
  const int floor = graph.currentFloor();
  auto& matches = answer.plane_matches;
  for (auto it = matches.begin(); it != matches.end();) {
    // Another floor's walls are held as they are: the robot does not see them now.
    if (graph.planes()[it->first].floor != floor) {
      ++it;
      continue;
    }
    const auto plane = by_id.find(it->first);
    if (plane == by_id.end()) {  // merged into another plane, or no longer a wall
      it = matches.erase(it);
      continue;
    }
    const bool agrees =
        plan_->matcher().planeAgrees(*plane->second, it->second, answer.P_T_M_x_y_yaw,
                                     options_.hold_angle_deg, options_.hold_distance);
    if (seen_now.count(it->first)) {
      ++seen_matched;
      seen_disagreeing += agrees ? 0 : 1;
    }
    if (!agrees) ++dropped_disagreeing_;
    it = agrees ? std::next(it) : matches.erase(it);
  }
  char text[256];
  if (seen_matched >= options_.lost_min_planes &&
      seen_disagreeing > options_.lost_disagreeing_share * seen_matched) {
    std::snprintf(text, sizeof text, "%d of the %d matched walls seen now disagree with the plan",
                  seen_disagreeing, seen_matched);
    return text;
  }
  // Too few walls of the plan held: lost when walls left the hold gate under this answer (the
  // plan disagreed with them), else thin evidence, not evidence against: unconfirmed.
  if (int(matches.size()) < options_.lost_min_held) {
    std::snprintf(text, sizeof text, "only %zu plan correspondences left", matches.size());
    if (dropped_disagreeing_ > 0) return text;
    unconfirmed_ = text;
  }
  return "";
}

std::string PlanAgreement::update(const MatchInput& input, const SGraph& graph,
                                  HeldAnswer& answer) {
  unconfirmed_.clear();
  left_outline_ = false;
  // The scan against the recent map and against the plan: the robot is not where the graph
  // thinks when both disagree, or when the plan disagrees more and more.
  if (std::string why = scanDisagreement(graph, answer); !why.empty()) return why;
  // The pose must be in the building.
  if (const auto pose = graph.latestPose()) {
    const Eigen::Vector2d p = answer.inP(pose->M_T_R.translation().head<2>());
    if (!plan_->building().contains(p)) {
      const Eigen::Vector2d in_B = p + plan_->B_t_P();
      char text[128];
      std::snprintf(text, sizeof text, "the pose (%.1f, %.1f) is outside the building", in_B.x(),
                    in_B.y());
      const auto& registration = graph.keyframes().back().registration;
      left_outline_ = registration.attempted && registration.inlier_share >= options_.suspect_share;
      return text;
    }
  }
  return heldDisagreement(input, graph, answer);
}

}  // namespace isg::slam
