#include "slam/isgraph/isgraph_localizer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "bim/agraph_factors.hpp"
#include "common/angles.hpp"
#include "slam/isgraph/merging_factors.hpp"
#include "slam/isgraph/room_hold.hpp"

namespace isg::slam {

namespace {

Eigen::Vector2d applyPlanar(const Eigen::Vector3d& x_y_yaw, const Eigen::Vector2d& p) {
  return Eigen::Rotation2Dd(x_y_yaw.z()) * p + x_y_yaw.head<2>();
}

}  // namespace

ISGraphLocalizer::ISGraphLocalizer(const Eigen::Isometry3d& R_T_L, const bim::AGraph& plan,
                                   const ISGraphOptions& options)
    : options_(options),
      B_t_P_(plan.localOrigin()),
      plan_in_P_(plan.translated(-B_t_P_)),
      plan_(&plan_in_P_),
      R_T_L_(R_T_L),
      plan_field_(plan_in_P_),
      graph_(R_T_L, options.sgraph),
      matcher_(plan_in_P_, options.matching),
      plan_state_(plan_in_P_) {
  // The box of the plan's walls and the margin: a pose outside it is no pose in the building.
  const Eigen::AlignedBox2d walls = plan_in_P_.surfaceBounds();
  const Eigen::Vector2d margin = Eigen::Vector2d::Constant(options.outside_margin);
  building_ = Eigen::AlignedBox2d(walls.min() - margin, walls.max() + margin);
  if (plan_in_P_.floors.size() > 1) {
    level_matcher_ = std::make_unique<LevelMatcher>(plan_in_P_, options.matching);
    flights_ = flightFootprints(plan_in_P_);
  }
  graph_.setWindowHook(
      [this](ceres::Problem& problem, const std::set<int>& planes, const std::vector<int>& rooms) {
        addPlanFactors(problem, planes, rooms);
      });
}

void ISGraphLocalizer::pushScan(const sensors::Scan& scan) {
  if (!graph_.addScan(scan)) return;
  const auto start = std::chrono::steady_clock::now();
  onKeyframe(scan.stamp);
  matching_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

sensors::StageTimes ISGraphLocalizer::stageTimes() const {
  sensors::StageTimes times = graph_.stageTimes();
  times.add("matching", matching_s_);
  return times;
}

bool ISGraphLocalizer::wantsScan(double stamp) const { return graph_.wouldKeyframe(stamp); }

Eigen::Vector3d ISGraphLocalizer::inB(const Eigen::Vector3d& P_T_M_x_y_yaw) const {
  return {P_T_M_x_y_yaw.x() + B_t_P_.x(), P_T_M_x_y_yaw.y() + B_t_P_.y(), P_T_M_x_y_yaw.z()};
}

Eigen::Vector3d ISGraphLocalizer::inP(const Eigen::Vector3d& B_T_M_x_y_yaw) const {
  return {B_T_M_x_y_yaw.x() - B_t_P_.x(), B_T_M_x_y_yaw.y() - B_t_P_.y(), B_T_M_x_y_yaw.z()};
}

std::optional<Eigen::Isometry3d> ISGraphLocalizer::mapInPlan() const {
  if (!localized_) return std::nullopt;
  const Eigen::Vector3d B_T_M = inB(P_T_M_x_y_yaw_);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(B_T_M.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(B_T_M.x(), B_T_M.y(), P_T_M_z_);
  return T;
}

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
    input.planes.push_back({i, p.map.plane, p.map.start, p.map.end});
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

void ISGraphLocalizer::record(double stamp, MatchStatus status, const std::string& reason) {
  if (status == status_ && !events_.empty()) return;
  status_ = status;
  events_.push_back({stamp, int(graph_.keyframes().size()) - 1, status, reason});
}

void ISGraphLocalizer::adopt(const Verification& answer, int level) {
  P_T_M_x_y_yaw_ = answer.x_y_yaw;
  plane_matches_.clear();
  room_matches_.clear();
  for (const auto& [s, a] : answer.planes) plane_matches_[s] = a;
  for (const auto& [s, a] : answer.rooms) room_matches_[s] = a;
  released_.clear();
  released_planes_.clear();
  released_surfaces_.clear();
  release_strikes_.clear();
  // z: walls do not observe it; the floor does. The floor of the answer's level, or of the first
  // matched room's.
  if (level < 0 && !answer.rooms.empty()) level = plan_->rooms[answer.rooms[0].second].floor;
  const double elevation = level >= 0              ? plan_->floors[level].elevation
                           : plan_->floors.empty() ? 0.0
                                                   : plan_->floors[0].elevation;
  // Before the floor is seen, the most it can be (SGraph::floorBound).
  P_T_M_z_ = elevation - graph_.floorHeight().value_or(graph_.floorBound().value_or(0.0));
  z_from_floor_ = graph_.floorHeight().has_value();
  level_ = level >= 0 ? level : 0;
  floor_levels_.clear();
  if (graph_.currentFloor() >= 0) floor_levels_[graph_.currentFloor()] = level_;
  localized_ = true;
  plan_shares_.clear();  // measured under another answer, or none
  plan_collapsed_ = 0;
}

double ISGraphLocalizer::planShare() const {
  const auto& keyframe = graph_.keyframes().back();
  if (keyframe.cloud.empty()) return -1.0;
  const Eigen::Isometry3d M_T_L = keyframe.pose() * R_T_L_;
  const double sensor_z = M_T_L.translation().z();
  int used = 0, near = 0;
  for (const auto& p : keyframe.cloud) {
    const Eigen::Vector3d q = M_T_L * p.cast<double>();
    if (q.z() < sensor_z - 0.4 || q.z() > sensor_z + 1.2) continue;  // floor, ceiling
    ++used;
    const Eigen::Vector2d in_P = applyPlanar(P_T_M_x_y_yaw_, q.head<2>());
    if (plan_field_.distance(in_P) <= options_.plan_share_distance) ++near;
  }
  return used > 0 ? double(near) / used : -1.0;
}

std::string ISGraphLocalizer::updateAgreement(const MatchInput& input) {
  char text[256];
  const auto& keyframe = graph_.keyframes().back();
  // The scan against the recent map and against the plan: the robot is not where the graph
  // thinks when both disagree, or when the plan disagrees more and more.
  const double plan_share = planShare();
  if (plan_share >= 0.0) {
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
    plan_collapsed_ = median > 0.0 && plan_share < options_.plan_share_collapse * median
                          ? plan_collapsed_ + 1
                          : 0;
    if (plan_collapsed_ >= 2) {
      std::snprintf(text, sizeof text,
                    "the scans no longer agree with the plan (%.0f %% of the wall points on a plan "
                    "wall, %.0f %% before)",
                    100.0 * plan_share, 100.0 * median);
      return text;
    }
    plan_shares_.push_back(plan_share);
    while (int(plan_shares_.size()) > options_.plan_share_history) plan_shares_.pop_front();
  }
  // The pose must be in the building.
  if (const auto pose = graph_.latestPose()) {
    const Eigen::Vector2d p = applyPlanar(P_T_M_x_y_yaw_, pose->M_T_R.translation().head<2>());
    if (!building_.contains(p)) {
      const Eigen::Vector2d in_B = p + B_t_P_;
      std::snprintf(text, sizeof text, "the pose (%.1f, %.1f) is outside the building", in_B.x(),
                    in_B.y());
      return text;
    }
  }
  // Held correspondences: those that left the hold gate are dropped; if most of the ones the
  // latest keyframe sees left it, the plan contradicts what the robot sees now.
  std::map<int, const MatchPlane*> by_id;
  for (const auto& plane : input.planes) by_id[plane.id] = &plane;
  std::set<int> seen_now;
  for (const auto& [plane, observation] : keyframe.observations) seen_now.insert(plane);
  int seen_matched = 0, seen_disagreeing = 0;
  const int floor = graph_.currentFloor();
  for (auto it = plane_matches_.begin(); it != plane_matches_.end();) {
    // Another floor's walls are held as they are: the robot does not see them now.
    if (graph_.planes()[it->first].floor != floor) {
      ++it;
      continue;
    }
    const auto plane = by_id.find(it->first);
    if (plane == by_id.end()) {  // merged into another plane, or no longer a wall
      it = plane_matches_.erase(it);
      continue;
    }
    const bool agrees = matcher_.planeAgrees(*plane->second, it->second, P_T_M_x_y_yaw_,
                                             options_.hold_angle_deg, options_.hold_distance);
    if (seen_now.count(it->first)) {
      ++seen_matched;
      seen_disagreeing += agrees ? 0 : 1;
    }
    it = agrees ? std::next(it) : plane_matches_.erase(it);
  }
  if (seen_matched >= options_.lost_min_planes &&
      seen_disagreeing > options_.lost_disagreeing_share * seen_matched) {
    std::snprintf(text, sizeof text, "%d of the %d matched walls seen now disagree with the plan",
                  seen_disagreeing, seen_matched);
    return text;
  }
  if (int(plane_matches_.size()) < options_.lost_min_held) {
    std::snprintf(text, sizeof text, "only %zu plan correspondences left", plane_matches_.size());
    return text;
  }
  return "";
}

std::vector<HeldWall> ISGraphLocalizer::heldWalls(const MatchInput& input,
                                                  std::vector<std::pair<int, int>>* held) const {
  std::map<int, const MatchPlane*> by_id;
  for (const auto& plane : input.planes) by_id[plane.id] = &plane;
  const int floor = graph_.currentFloor();
  const Eigen::Rotation2Dd P_R_M(P_T_M_x_y_yaw_.z());
  std::vector<HeldWall> walls;
  std::map<std::string, int> walls_by_name;
  for (const auto& [s, a] : plane_matches_) {
    const auto plane = by_id.find(s);
    if (graph_.planes()[s].floor != floor || plane == by_id.end()) continue;
    const bim::Plane& surface = plan_->surfaces[a].plane;
    HeldWall wall;
    wall.middle = applyPlanar(P_T_M_x_y_yaw_, 0.5 * (plane->second->start + plane->second->end));
    wall.length = plane->second->length();
    wall.normal = surface.normal.head<2>().normalized();
    wall.offset = surface.signedDistance({wall.middle.x(), wall.middle.y(), 0.0});
    wall.angle =
        common::angleDifference(common::headingOf(P_R_M * plane->second->plane.normal.head<2>()),
                                common::headingOf(wall.normal));
    // Plan walls by name; a flight's faces each stand alone.
    const std::string& name = plan_->surfaces[a].wall;
    wall.wall = name.empty() ? -1 - a
                             : walls_by_name.emplace(name, int(walls_by_name.size())).first->second;
    walls.push_back(wall);
    if (held) held->emplace_back(s, a);
  }
  return walls;
}

void ISGraphLocalizer::releaseDeviatingWalls(const MatchInput& input, double stamp,
                                             int strikes_needed) {
  std::vector<std::pair<int, int>> held;  // (S-plane, A-surface) of each of `walls`
  const std::vector<HeldWall> walls = heldWalls(input, &held);
  const std::vector<WallResidual> residuals = residualsAgainstOthers(walls, options_.release);
  int judged = 0;
  std::vector<std::size_t> due;
  // Strikes count keyframes in a row: a plane not judged beyond now (within, or not judged at all,
  // as when it is on another floor) starts again from none.
  std::map<int, int> strikes;
  for (std::size_t k = 0; k < residuals.size(); ++k) {
    judged += residuals[k].judged ? 1 : 0;
    if (!residuals[k].beyond(options_.release)) continue;
    const int s = held[k].first;
    const auto before = release_strikes_.find(s);
    strikes[s] = 1 + (before == release_strikes_.end() ? 0 : before->second);
    if (strikes[s] >= strikes_needed) due.push_back(k);
  }
  release_strikes_ = std::move(strikes);
  // Most of the judged walls disagreeing is not a building built off its plan but an answer off
  // the building: that is for the hold gate and the contradiction check to settle.
  if (2 * int(due.size()) > judged) return;
  for (std::size_t k : due) {
    const auto [s, a] = held[k];
    released_.push_back({stamp, s, a, residuals[k].offset, residuals[k].angle});
    released_planes_.insert(s);
    released_surfaces_[a] = residuals[k].offset;
    plane_matches_.erase(s);
    release_strikes_.erase(s);
  }
}

void ISGraphLocalizer::assumeMatch(double stamp, const Eigen::Vector3d& x_y_yaw,
                                   const std::string& reason) {
  const MatchInput input = matchInput();
  record(stamp, MatchStatus::kMatched, reason);
  // With several levels, the level under which the hint explains most.
  int level = -1;
  Verification answer = matcher_.verify(input, inP(x_y_yaw));
  if (level_matcher_) {
    for (int l = 0; l < level_matcher_->levels(); ++l) {
      Verification on_level = level_matcher_->verify(input, inP(x_y_yaw), l);
      if (level < 0 || on_level.score > answer.score) answer = std::move(on_level), level = l;
    }
  }
  adopt(answer, level);
  rooms_at_last_attempt_ = input.rooms.size();
  keyframes_at_last_attempt_ = int(graph_.keyframes().size());
}

void ISGraphLocalizer::lose(double stamp, const std::string& reason) {
  record(stamp, MatchStatus::kLost, reason);
  ++losses_;
  localized_ = false;
  plane_matches_.clear();
  room_matches_.clear();
  released_.clear();
  released_planes_.clear();
  released_surfaces_.clear();
  release_strikes_.clear();
  floor_levels_.clear();
  plan_shares_.clear();
  plan_collapsed_ = 0;
  graph_.startNewSegment(stamp, reason);
  rooms_at_last_attempt_ = 0;
  keyframes_at_last_attempt_ = 0;
}

void ISGraphLocalizer::checkForContradiction(double stamp) {
  // The S-Graph as it would be without the merge: optimised on its own evidence, so that the
  // answer it is matched to does not bias the judgement.
  SGraph unmerged = graph_;
  unmerged.optimiseAll(false);
  const MatchInput input = matchInputOf(unmerged, options_.sgraph.rooms.min_wall_height);
  int level = -1;
  MatchResult result = matchNow(input, &level);
  matching_times_.push_back(result.seconds);
  last_match_ = result.translated(B_t_P_);
  // Twice the clustering tolerances: the merge has moved P_T_M a little since it was adopted.
  const Eigen::Vector2d middle = GraphMatcher::middleOf(input);
  const bool same_level = !level_matcher_ || level == level_;
  const GraphMatcher& held_matcher = level_matcher_ ? level_matcher_->matcher(level_) : matcher_;
  if (result.status != MatchStatus::kMatched) return;  // the merge stands on its own evidence
  if (same_level && matcher_.sameAnswer(result.best.x_y_yaw, P_T_M_x_y_yaw_, middle, 2.0)) return;
  // The new answer must also lead the one held now decisively, on the same map.
  const GraphMatcher& new_matcher = level_matcher_ ? level_matcher_->matcher(level) : matcher_;
  if (!new_matcher.decisive(new_matcher.distinguish(
          input, result.best, held_matcher.verify(input, P_T_M_x_y_yaw_), &held_matcher))) {
    return;
  }
  // A unique answer elsewhere: the first match was wrong.
  const double apart =
      (applyPlanar(result.best.x_y_yaw, middle) - applyPlanar(P_T_M_x_y_yaw_, middle)).norm();
  record(stamp, MatchStatus::kContradicted,
         "a new unique answer " + std::to_string(apart) + " m away: " + result.reason);
  ++contradictions_;
  // Adopt the new one on the unmerged graph, and re-optimise every keyframe under it, so that
  // nothing stays where the old B_T_M pulled it.
  graph_ = std::move(unmerged);
  adopt(result.best, level);
  refineAnswer(input, stamp);  // as a first answer is (onKeyframe)
  graph_.optimiseAll(true);
  record(stamp, MatchStatus::kMatched, result.reason);
}

MatchResult ISGraphLocalizer::matchNow(const MatchInput& input, int* level) const {
  if (!level_matcher_) {
    *level = -1;
    return matcher_.match(input);
  }
  LevelMatch match = level_matcher_->match(input);
  *level = match.level;
  return std::move(match.result);
}

Verification ISGraphLocalizer::verifyNow(const MatchInput& input,
                                         const Eigen::Vector3d& P_T_M_x_y_yaw) const {
  if (!level_matcher_) return matcher_.verify(input, P_T_M_x_y_yaw);
  return level_matcher_->verify(input, P_T_M_x_y_yaw, level_);
}

int ISGraphLocalizer::levelAtHeightOf(int floor) const {
  const auto& floors = graph_.floors();
  if (floor_levels_.empty() || floor < 0 || floor >= int(floors.size())) return -1;
  // From the lowest-numbered floor whose level is known; any would do: M is one frame, and the
  // heights of its floors differ by the storeys climbed.
  const auto& [known_floor, known_level] = *floor_levels_.begin();
  const double elevation =
      plan_->floors[known_level].elevation + floors[floor].robot_z - floors[known_floor].robot_z;
  int best = -1;
  for (int l = 0; l < int(plan_->floors.size()); ++l) {
    const double off = std::abs(plan_->floors[l].elevation - elevation);
    if (off <= options_.level_tolerance &&
        (best < 0 || off < std::abs(plan_->floors[best].elevation - elevation))) {
      best = l;
    }
  }
  return best;
}

std::string ISGraphLocalizer::offFlight() const {
  const double elevation = plan_->floors[level_].elevation;
  const Eigen::Vector2d p =
      applyPlanar(P_T_M_x_y_yaw_, graph_.keyframes().back().pose().translation().head<2>());
  double nearest = std::numeric_limits<double>::infinity();
  for (const auto& flight : flights_) {
    if (flight.joins(elevation, options_.level_tolerance)) {
      nearest = std::min(nearest, flight.distance(p));
    }
  }
  if (nearest <= options_.flight_margin) return "";
  const Eigen::Vector2d in_B = p + B_t_P_;
  char text[200];
  if (std::isinf(nearest)) {
    std::snprintf(text, sizeof text,
                  "the robot is on stairs at (%.1f, %.1f), and no flight of the plan joins level "
                  "%s",
                  in_B.x(), in_B.y(), plan_->floors[level_].id.c_str());
  } else {
    std::snprintf(text, sizeof text,
                  "the robot is on stairs at (%.1f, %.1f), %.1f m from every flight that joins "
                  "level %s",
                  in_B.x(), in_B.y(), nearest, plan_->floors[level_].id.c_str());
  }
  return text;
}

std::string ISGraphLocalizer::followFloor(double stamp) {
  const int floor = graph_.currentFloor();
  if (!level_matcher_) {
    // The floor's height as it is known now (its observations accumulate), or before it was
    // seen, the most it can be.
    if (graph_.floorHeight()) {
      P_T_M_z_ = plan_->floors[level_].elevation - *graph_.floorHeight();
      z_from_floor_ = true;
    } else if (!z_from_floor_ && graph_.floorBound()) {
      P_T_M_z_ = plan_->floors[level_].elevation - *graph_.floorBound();
    }
    return "";
  }
  if (floor < 0) return "";
  // Between floors (the current floor is the last one stood on).
  if (graph_.keyframes().back().floor < 0) return offFlight();
  const auto known = floor_levels_.find(floor);
  if (known != floor_levels_.end()) {
    level_ = known->second;
  } else {
    const int level = levelAtHeightOf(floor);
    if (level < 0) {
      char text[160];
      std::snprintf(
          text, sizeof text,
          "the robot reached a floor %.1f m from where it was matched, and no level of "
          "the plan is there",
          graph_.floors()[floor].robot_z - graph_.floors()[floor_levels_.begin()->first].robot_z);
      return text;
    }
    floor_levels_[floor] = level;
    level_ = level;
    level_changes_.push_back({stamp, floor, level});
  }
  if (const auto height = graph_.floorHeight(floor)) {
    P_T_M_z_ = plan_->floors[level_].elevation - *height;
    z_from_floor_ = true;
  }
  return "";
}

void ISGraphLocalizer::onKeyframe(double stamp) {
  const int keyframes = int(graph_.keyframes().size());
  MatchInput input = matchInput();
  if (localized_) {
    std::string why = followFloor(stamp);
    if (why.empty()) why = updateAgreement(input);
    if (!why.empty()) {
      lose(stamp, why);
      return;
    }
    releaseDeviatingWalls(input, stamp, options_.release.strikes);
    if (moveToConsensus(input, stamp)) return;
    // New S-planes gain correspondences at the current P_T_M; held ones stay as they are, and
    // released ones stay released.
    const Verification now = verifyNow(input, P_T_M_x_y_yaw_);
    for (const auto& [plane, surface] : now.planes) {
      if (!released_planes_.count(plane) && !released_surfaces_.count(surface)) {
        plane_matches_.emplace(plane, surface);
      }
    }
    for (const auto& [s, a] : now.rooms) room_matches_.emplace(s, a);
  } else if (keyframes > 1 && graph_.keyframes().back().onFloor() &&
             graph_.keyframes().back().registration.attempted &&
             !graph_.keyframes().back().registration.agrees) {
    // Not localized, and the world stopped agreeing with the map: the map so far would mislead
    // the matcher. Start again from here.
    graph_.startNewSegment(stamp, "the scan does not agree with the recent map");
    rooms_at_last_attempt_ = 0;
    keyframes_at_last_attempt_ = 0;
    return;
  }
  const bool new_rooms = input.rooms.size() != rooms_at_last_attempt_;
  const bool due =
      !localized_ && keyframes - keyframes_at_last_attempt_ >= options_.retry_keyframes;
  if (!new_rooms && !due) return;
  rooms_at_last_attempt_ = input.rooms.size();
  keyframes_at_last_attempt_ = keyframes;
  if (localized_) {
    checkForContradiction(stamp);
    return;
  }
  int level = -1;
  MatchResult result = matchNow(input, &level);
  matching_times_.push_back(result.seconds);
  last_match_ = result.translated(B_t_P_);
  record(stamp, result.status, result.reason);
  if (result.status != MatchStatus::kMatched) return;
  adopt(result.best, level);
  refineAnswer(input, stamp);
}

bool ISGraphLocalizer::moveToConsensus(const MatchInput& input, double stamp) {
  // Only new walls can change the vote; and only on a floor (between floors, the planes mapped
  // from the flight are not yet of any level).
  if (input.planes.size() == planes_at_last_vote_ || graph_.keyframes().back().floor < 0) {
    return false;
  }
  planes_at_last_vote_ = input.planes.size();
  // The vote on the level's own matcher; the answers verified again with their indices into the
  // whole A-Graph (verifyNow), which the correspondences hold.
  const GraphMatcher& matcher = level_matcher_ ? level_matcher_->matcher(level_) : matcher_;
  const Eigen::Vector3d voted =
      matcher.consensus(input, matcher.verify(input, P_T_M_x_y_yaw_)).x_y_yaw;
  const Eigen::Vector2d middle = GraphMatcher::middleOf(input);
  const double apart = (applyPlanar(voted, middle) - applyPlanar(P_T_M_x_y_yaw_, middle)).norm();
  if (apart < options_.min_answer_move) return false;
  const Verification moved = verifyNow(input, voted);
  answer_moves_.push_back({stamp, apart, matcher.wallsAgreeing(input, P_T_M_x_y_yaw_),
                           matcher.wallsAgreeing(input, voted)});
  // The vote was taken on the S-Graph as merged, so the move is made on it; every keyframe is
  // re-optimised under the new correspondences below. Only where in the plane, and only this
  // floor's correspondences: the level, the height and the other floors' walls stay.
  // What this floor's walls were judged under the old answer no longer holds: its releases are
  // undone (the log keeps them).
  for (const ReleasedWall& r : released_) {
    if (std::any_of(input.planes.begin(), input.planes.end(),
                    [&](const MatchPlane& p) { return p.id == r.plane; })) {
      released_planes_.erase(r.plane);
      released_surfaces_.erase(r.surface);
    }
  }
  for (const MatchPlane& plane : input.planes) release_strikes_.erase(plane.id);
  P_T_M_x_y_yaw_ = moved.x_y_yaw;
  for (const MatchPlane& plane : input.planes) plane_matches_.erase(plane.id);
  for (const MatchRoom& room : input.rooms) room_matches_.erase(room.id);
  for (const auto& [plane, surface] : moved.planes) {
    if (!released_planes_.count(plane) && !released_surfaces_.count(surface)) {
      plane_matches_[plane] = surface;
    }
  }
  for (const auto& [s, a] : moved.rooms) room_matches_[s] = a;
  // Not judged again at once, as a new answer's walls are (refineAnswer): the map was merged under
  // the old answer, and in a long building it bent with it; the walls it left off their surfaces
  // are judged on the usual streak of keyframes once the merge has worked under the new answer.
  // Nor are the surfaces the old answer sat on and the new one leaves released: far from the
  // robot, drift rather than the building may put them off (measured, docs/matching.md).
  refitAnswer(input);
  graph_.optimiseAll(true);
  return true;
}

void ISGraphLocalizer::refineAnswer(const MatchInput& input, double stamp) {
  // The walls of a new answer were each seen over many keyframes already: judged now, before the
  // first merge, those built off their plan do not pull it for the keyframes a streak would take.
  releaseDeviatingWalls(input, stamp, 1);
  refitAnswer(input);
}

void ISGraphLocalizer::refitAnswer(const MatchInput& input) {
  // The answer was fitted to all of its walls, those built off too: refitted to the walls held,
  // robustly, the merge starts from where they agree.
  const auto correction = correctionOfAll(heldWalls(input, nullptr), options_.release);
  if (!correction) return;
  const Eigen::Rotation2Dd turn(correction->z());
  P_T_M_x_y_yaw_.head<2>() = turn * P_T_M_x_y_yaw_.head<2>() + correction->head<2>();
  P_T_M_x_y_yaw_.z() += correction->z();
}

void ISGraphLocalizer::addSurface(ceres::Problem& problem, int surface) {
  if (!surfaces_in_problem_.insert(surface).second) return;
  double* block = plan_state_.planes[surface].data();
  problem.AddParameterBlock(block, 4, &plane_manifold_);
  problem.AddResidualBlock(
      bim::PlanePriorFactor::create(bim::toVector(plan_->surfaces[surface].plane),
                                    options_.plan.plane_angle, options_.plan.plane_distance),
      nullptr, block);
}

std::optional<std::array<double, 2>> ISGraphLocalizer::widthsAlongPlanPairs(
    int room, const bim::RoomNode& node) const {
  const auto& s_room = graph_.roomCandidates()[room];
  if (!s_room.candidate.four_wall || node.pairs.size() != 2) return std::nullopt;
  const auto& planes = graph_.planes();
  const Eigen::Rotation2Dd P_R_M(P_T_M_x_y_yaw_.z());
  std::array<double, 2> widths{0.0, 0.0};
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector2d plan_normal =
        plan_->surfaces[node.pairs[k][0]].plane.normal.head<2>().normalized();
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

void ISGraphLocalizer::addPlanFactors(ceres::Problem& problem, const std::set<int>& planes,
                                      const std::vector<int>& rooms) {
  if (!localized_) return;
  surfaces_in_problem_.clear();
  // Whether the window's correspondences fix P_T_M: x and y need surface normals in two
  // directions (or a matched four-wall room); yaw any one surface.
  std::vector<Eigen::Vector2d> normals;
  bool room_fixes = false;
  bool any = false;
  for (int p : planes) {
    const auto it = plane_matches_.find(p);
    if (it == plane_matches_.end()) continue;
    any = true;
    normals.push_back(plan_->surfaces[it->second].plane.normal.head<2>().normalized());
    addSurface(problem, it->second);
    problem.AddResidualBlock(
        PlanePlaneFactor::create(options_.sigma_plane_angle, options_.sigma_plane_distance),
        &huber_, graph_.planeParameters(p), P_T_M_x_y_yaw_.data(),
        plan_state_.planes[it->second].data());
  }
  if (!any) return;
  for (int r : rooms) {
    const auto it = room_matches_.find(r);
    if (it == room_matches_.end()) continue;
    const bim::RoomNode& node = plan_->rooms[it->second];
    // A corridor's S-centre lies wherever along it the robot first saw it, not at the plan's
    // centre: only four-wall rooms give a room-to-room factor.
    if (node.kind != bim::RoomKind::kFourWall) continue;
    // Held along a pair only while that pair's walls stand where the plan has them, as far as
    // the map can tell (holdsAlongPair: room_hold.hpp); along the other pair's normal alone, or
    // not at all, otherwise. Measured in docs/matching.md, "Rooms with a wall built off".
    const auto widths = widthsAlongPlanPairs(r, node);
    std::vector<int> held_pairs;
    for (int k = 0; k < 2; ++k) {
      RoomPairEvidence pair;
      pair.plan_width = node.widths[k];
      pair.map_width = widths ? (*widths)[k] : node.widths[k];
      for (int a : node.pairs[k]) {
        const auto released = released_surfaces_.find(a);
        if (released != released_surfaces_.end()) {
          pair.released_offset = std::max(pair.released_offset, std::abs(released->second));
        }
      }
      if (holdsAlongPair(pair, options_.sigma_room)) held_pairs.push_back(k);
    }
    if (held_pairs.empty()) continue;
    for (const auto& pair : node.pairs) addSurface(problem, pair[0]), addSurface(problem, pair[1]);
    double* centre = plan_state_.rooms[it->second].data();
    problem.AddResidualBlock(
        bim::FourWallRoomFactor::create(options_.plan.room), nullptr, centre,
        plan_state_.planes[node.pairs[0][0]].data(), plan_state_.planes[node.pairs[0][1]].data(),
        plan_state_.planes[node.pairs[1][0]].data(), plan_state_.planes[node.pairs[1][1]].data());
    if (held_pairs.size() == 2) {
      problem.AddResidualBlock(RoomRoomFactor::create(options_.sigma_room), nullptr,
                               graph_.roomCentre(r), P_T_M_x_y_yaw_.data(), centre);
      room_fixes = true;
      continue;
    }
    const Eigen::Vector2d normal =
        plan_->surfaces[node.pairs[held_pairs[0]][0]].plane.normal.head<2>().normalized();
    problem.AddResidualBlock(RoomRoomAlongFactor::create(normal, options_.sigma_room), nullptr,
                             graph_.roomCentre(r), P_T_M_x_y_yaw_.data(), centre);
    normals.push_back(normal);
  }
  const double spread = std::sin(options_.min_normal_spread_deg * std::numbers::pi / 180.0);
  bool spans = room_fixes;
  for (std::size_t i = 0; i < normals.size() && !spans; ++i) {
    for (std::size_t j = i + 1; j < normals.size() && !spans; ++j) {
      spans = std::abs(normals[i].x() * normals[j].y() - normals[i].y() * normals[j].x()) >= spread;
    }
  }
  problem.AddResidualBlock(
      PlanarPriorFactor::create(P_T_M_x_y_yaw_, options_.sigma_B_T_M_translation,
                                options_.sigma_B_T_M_yaw),
      nullptr, P_T_M_x_y_yaw_.data());
  if (!spans) {
    problem.SetParameterBlockConstant(P_T_M_x_y_yaw_.data());
    ++held_constant_;
  }
  // The plan's walls between surfaces in the problem.
  for (std::size_t w = 0; w < plan_->walls.size(); ++w) {
    const auto& wall = plan_->walls[w];
    if (!surfaces_in_problem_.count(wall.left_surface) ||
        !surfaces_in_problem_.count(wall.right_surface)) {
      continue;
    }
    problem.AddResidualBlock(bim::WallFactor::create(wall.anchor, options_.plan.wall), nullptr,
                             plan_state_.walls[w].data(),
                             plan_state_.planes[wall.left_surface].data(),
                             plan_state_.planes[wall.right_surface].data());
  }
}

std::vector<StatusChange> ISGraphLocalizer::statusChanges() const { return events_; }

nlohmann::json ISGraphLocalizer::graph() const {
  nlohmann::json out = graph_.toJson();
  nlohmann::json planes = nlohmann::json::array(), rooms = nlohmann::json::array(),
                 events = nlohmann::json::array();
  for (const auto& [s, a] : plane_matches_) planes.push_back({s, plan_->surfaces[a].id});
  for (const auto& [s, a] : room_matches_) rooms.push_back({s, plan_->rooms[a].id});
  nlohmann::json released = nlohmann::json::array();
  for (const auto& r : released_) {
    released.push_back({{"stamp", r.stamp},
                        {"plane", r.plane},
                        {"surface", plan_->surfaces[r.surface].id},
                        {"offset_m", r.offset},
                        {"angle_deg", common::degrees(r.angle)}});
  }
  for (const auto& e : events_) {
    events.push_back({{"stamp", e.stamp},
                      {"keyframe", e.keyframe},
                      {"status", toString(e.status)},
                      {"reason", e.reason}});
  }
  nlohmann::json moves = nlohmann::json::array();
  for (const auto& m : answer_moves_) {
    moves.push_back({{"stamp", m.stamp},
                     {"moved_m", m.distance},
                     {"walls_agreeing_before", m.walls_before},
                     {"walls_agreeing_after", m.walls_after}});
  }
  nlohmann::json is_graph = {{"status", toString(status_)},
                             {"localized", localized_},
                             {"contradictions", contradictions_},
                             {"answer_moves", moves},
                             {"times_lost", losses_},
                             {"windows_with_B_T_M_held", held_constant_},
                             {"plane_matches", planes},
                             {"released_walls", released},
                             {"room_matches", rooms},
                             {"events", events}};
  if (localized_) {
    const Eigen::Vector3d B_T_M = inB(P_T_M_x_y_yaw_);
    is_graph["B_T_M"] = {{"x", B_T_M.x()}, {"y", B_T_M.y()}, {"z", P_T_M_z_}, {"yaw", B_T_M.z()}};
    if (level_ >= 0 && level_ < int(plan_->floors.size())) {
      is_graph["level"] = plan_->floors[level_].id;
    }
    nlohmann::json floor_levels = nlohmann::json::object();
    for (const auto& [floor, level] : floor_levels_) {
      floor_levels[std::to_string(floor)] = plan_->floors[level].id;
    }
    is_graph["floor_levels"] = floor_levels;
  }
  nlohmann::json level_changes = nlohmann::json::array();
  for (const auto& change : level_changes_) {
    level_changes.push_back({{"stamp", change.stamp},
                             {"floor", change.floor},
                             {"level", plan_->floors[change.level].id}});
  }
  if (!level_changes.empty()) is_graph["level_changes"] = level_changes;
  if (last_match_) is_graph["last_match"] = last_match_->toJson();
  out["method"] = name();
  out["matching"] = is_graph;
  return out;
}

}  // namespace isg::slam
