#include "slam/isgraph/isgraph_localizer.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <set>
#include <string>

#include "common/angles.hpp"
#include "slam/isgraph/isgraph_json.hpp"

namespace isg::slam {

namespace {

FloorFollower::Options floorOptions(const ISGraphOptions& o) {
  return {o.level_tolerance, o.flight_margin};
}

PlanAgreement::Options agreementOptions(const ISGraphOptions& o) {
  PlanAgreement::Options a;
  a.hold_angle_deg = o.hold_angle_deg;
  a.hold_distance = o.hold_distance;
  a.lost_min_planes = o.lost_min_planes;
  a.lost_disagreeing_share = o.lost_disagreeing_share;
  a.lost_min_held = o.lost_min_held;
  a.plan_share_distance = o.plan_share_distance;
  a.suspect_share = o.suspect_share;
  a.plan_share_drop = o.plan_share_drop;
  a.plan_share_collapse = o.plan_share_collapse;
  a.plan_share_history = o.plan_share_history;
  return a;
}

PlanMerger::Options mergerOptions(const ISGraphOptions& o) {
  PlanMerger::Options m;
  m.plan = o.plan;
  m.sigma_plane_angle = o.sigma_plane_angle;
  m.sigma_plane_distance = o.sigma_plane_distance;
  m.sigma_room = o.sigma_room;
  m.sigma_B_T_M_translation = o.sigma_B_T_M_translation;
  m.sigma_B_T_M_yaw = o.sigma_B_T_M_yaw;
  m.min_normal_spread_deg = o.min_normal_spread_deg;
  m.jambs = o.jambs;
  return m;
}

}  // namespace

ISGraphLocalizer::ISGraphLocalizer(const Eigen::Isometry3d& R_T_L, const bim::AGraph& plan,
                                   const ISGraphOptions& options)
    : options_(options),
      R_T_L_(R_T_L),
      plan_(plan, options.matching, options.outside_margin),
      graph_(R_T_L, options.sgraph),
      released_(options.release),
      floors_(plan_, floorOptions(options)),
      agreement_(plan_, R_T_L, agreementOptions(options)),
      merger_(plan_, mergerOptions(options)) {
  graph_.setWindowHook(
      [this](ceres::Problem& problem, const std::set<int>& planes, const std::vector<int>& rooms) {
        merger_.addFactors(problem, planes, rooms, graph_, answer_, released_);
      });
}

void ISGraphLocalizer::pushScan(const sensors::Scan& scan) {
  if (!graph_.addScan(scan)) {
    // A start given at a stamp is taken at the first scan from it on, keyframe or not: a walker
    // standing there makes no keyframe for seconds, and each scan unplaced is a pose unestimated
    // (the floor-plan benchmark scores nothing below 99 % of its poses).
    if (stamped_start_ && scan.stamp >= stamped_start_->stamp) {
      takeStampedStart();
      if (given_start_) {
        const Eigen::Vector3d start = *given_start_;
        given_start_.reset();
        assumeMatch(scan.stamp, start, "the start pose given");
      }
    }
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  onKeyframe(scan.stamp);
  const auto jambs_start = std::chrono::steady_clock::now();
  matching_s_ += std::chrono::duration<double>(jambs_start - start).count();
  noteJambs();
  jambs_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - jambs_start).count();
}

sensors::StageTimes ISGraphLocalizer::stageTimes() const {
  sensors::StageTimes times = graph_.stageTimes();
  times.add("matching", matching_s_ - contradiction_s_ - bend_s_);
  times.add("contradiction checks", contradiction_s_);
  times.add("door jambs", jambs_s_);
  times.add("whole-map bends", bend_s_);
  return times;
}

void ISGraphLocalizer::noteJambs() {
  const auto& keyframes = graph_.keyframes();
  const int k = int(keyframes.size()) - 1;
  if (!answer_.localized || k < 0 || !keyframes.back().onFloor() || !graph_.keyframeScan()) return;
  // Only keyframes a window can still move need their jambs.
  merger_.noteKeyframe(k, *graph_.keyframeScan(), answer_.P_T_M() * keyframes.back().pose(), R_T_L_,
                       k - options_.sgraph.window - 1);
}

bool ISGraphLocalizer::wantsScan(double stamp) const { return graph_.wouldKeyframe(stamp); }

std::optional<Eigen::Isometry3d> ISGraphLocalizer::mapInPlan() const {
  if (!answer_.localized) return std::nullopt;
  const Eigen::Vector3d B_T_M = plan_.inB(answer_.P_T_M_x_y_yaw);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(B_T_M.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(B_T_M.x(), B_T_M.y(), answer_.P_T_M_z);
  return T;
}

bool ISGraphLocalizer::planConfirms() const {
  if (!answer_.localized || !agreement_.unconfirmed().empty()) return false;
  const auto& keyframes = graph_.keyframes();
  const std::size_t window = std::size_t(std::max(1, options_.sgraph.window));
  for (std::size_t i = keyframes.size() > window ? keyframes.size() - window : 0;
       i < keyframes.size(); ++i) {
    for (const auto& [plane, observation] : keyframes[i].observations) {
      if (answer_.plane_matches.count(plane)) return true;
    }
  }
  return false;
}

void ISGraphLocalizer::record(double stamp, MatchStatus status, const std::string& reason) {
  log_.record(stamp, int(graph_.keyframes().size()) - 1, status, reason);
}

void ISGraphLocalizer::adopt(const Verification& answer, int level) {
  answer_.take(answer);
  outside_answer_.reset();
  released_.clear();
  merger_.forgetKeyframes();  // gathered under another answer
  // The floor of the answer's level, or of the first matched room's.
  if (level < 0 && !answer.rooms.empty()) {
    level = plan_.agraph().rooms[answer.rooms[0].second].floor;
  }
  floors_.start(level, graph_, answer_);
  answer_.localized = true;
  agreement_.clear();  // measured under another answer, or none
}

void ISGraphLocalizer::assumeMatch(double stamp, const Eigen::Vector3d& x_y_yaw,
                                   const std::string& reason) {
  const MatchInput input = matchInput();
  record(stamp, MatchStatus::kMatched, reason);
  // With several levels, the level under which the hint explains most.
  int level = -1;
  const Verification answer = plan_.verifyOnBestLevel(input, plan_.inP(x_y_yaw), &level);
  adopt(answer, level);
  rooms_at_last_attempt_ = input.rooms.size();
  keyframes_at_last_attempt_ = int(graph_.keyframes().size());
}

bool ISGraphLocalizer::waitingOutside() {
  // About 60 m of walk at a keyframe a metre: a part of a site beyond its plan is walked back out
  // of within that; an answer that slid out and stays out is matched anew after it.
  constexpr int kOutsideWaitKeyframes = 60;
  if (!outside_answer_) return false;
  const auto pose = graph_.latestPose();
  const bool outside = pose && !plan_.building().contains(HeldAnswer::applyPlanar(
                                   *outside_answer_, pose->M_T_R.translation().head<2>()));
  if (outside && ++outside_keyframes_ <= kOutsideWaitKeyframes) return true;
  outside_answer_.reset();
  // Back within the plan: match now, on the whole map.
  rooms_at_last_attempt_ = 0;
  keyframes_at_last_attempt_ = 0;
  return false;
}

void ISGraphLocalizer::lose(double stamp, const std::string& reason, bool keep_map) {
  record(stamp, MatchStatus::kLost, reason);
  log_.lost();
  outside_answer_.reset();
  if (keep_map) {
    outside_answer_ = answer_.P_T_M_x_y_yaw;
    outside_keyframes_ = 0;
  }
  answer_.clear();
  released_.clear();
  merger_.forgetKeyframes();
  floors_.clear();
  agreement_.clear();
  // A map that still agrees with every scan is kept: the matcher finds the answer again on all
  // of it once the robot is back within the plan, rather than on a fresh segment that holds only
  // what lay beyond the plan.
  if (!keep_map) graph_.startNewSegment(stamp, reason);
  rooms_at_last_attempt_ = 0;
  rooms_at_last_check_ = 0;
  keyframes_at_last_attempt_ = 0;
}

void ISGraphLocalizer::checkForContradiction(double stamp) {
  // The S-Graph as it would be without the merge: optimised on its own evidence, so that the
  // answer it is matched to does not bias the judgement.
  SGraph unmerged = graph_;
  unmerged.optimiseAll(false);
  const MatchInput input = matchInputOf(unmerged, options_.sgraph.rooms.min_wall_height);
  int level = -1;
  MatchResult result = plan_.match(input, &level, graph_.pool());
  log_.attempted(result.translated(plan_.B_t_P()));
  // Twice the clustering tolerances: the merge has moved P_T_M a little since it was adopted.
  const Eigen::Vector2d middle = GraphMatcher::middleOf(input);
  const bool same_level = !plan_.severalLevels() || level == floors_.level();
  const GraphMatcher& held_matcher = plan_.matcherOf(floors_.level());
  if (result.status != MatchStatus::kMatched) return;  // the merge stands on its own evidence
  const Eigen::Vector3d& held = answer_.P_T_M_x_y_yaw;
  if (same_level && plan_.matcher().sameAnswer(result.best.x_y_yaw, held, middle, 2.0)) return;
  // The new answer must also lead the one held now decisively, on the same map.
  const GraphMatcher& new_matcher = plan_.matcherOf(level);
  if (!new_matcher.decisive(new_matcher.distinguish(
          input, result.best, held_matcher.verify(input, held), &held_matcher))) {
    return;
  }
  const double apart =
      (HeldAnswer::applyPlanar(result.best.x_y_yaw, middle) - answer_.inP(middle)).norm();
  const auto recent = recentLeadForHeld(result.best.x_y_yaw, level);
  if (recent && recent->decisive) {
    log_.refused({stamp, apart, recent->describe()});
    // The whole map preferred a rigid answer elsewhere: it bent. Bent onto the plan at the next
    // keyframe.
    keyframes_at_last_bend_ = -options_.bend_keyframes;
    return;
  }
  // A unique answer elsewhere: the first match was wrong.
  record(stamp, MatchStatus::kContradicted,
         "a new unique answer " + std::to_string(apart) + " m away: " + result.reason +
             (recent ? "; " + recent->describe() : ""));
  log_.contradicted();
  // Adopt the new one on the unmerged graph, and re-optimise every keyframe under it, so that
  // nothing stays where the old B_T_M pulled it.
  graph_ = std::move(unmerged);
  adopt(result.best, level);
  refineAnswer(input, stamp);  // as a first answer is (onKeyframe)
  graph_.optimiseAll(true);
  record(stamp, MatchStatus::kMatched, result.reason);
}

void ISGraphLocalizer::bendMapOntoPlan(double stamp) {
  const auto start = std::chrono::steady_clock::now();
  keyframes_at_last_bend_ = int(graph_.keyframes().size());
  graph_.optimiseAll(true);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  bend_s_ += seconds;
  bends_.push_back({stamp, keyframes_at_last_bend_, int(graph_.confirmedRooms().size()), seconds});
}

std::optional<ISGraphLocalizer::RecentLead> ISGraphLocalizer::recentLeadForHeld(
    const Eigen::Vector3d& other, int other_level) const {
  if (options_.contradiction_recent_keyframes <= 0) return std::nullopt;
  const MatchInput recent =
      recentSightingsOf(graph_, R_T_L_, options_.contradiction_recent_keyframes,
                        options_.sgraph.rooms.min_wall_height);
  if (recent.planes.empty()) return std::nullopt;
  const GraphMatcher& held_matcher = plan_.matcherOf(floors_.level());
  const GraphMatcher& other_matcher = plan_.matcherOf(other_level);
  RecentLead lead;
  lead.distinction =
      held_matcher.distinguish(recent, held_matcher.verify(recent, answer_.P_T_M_x_y_yaw),
                               other_matcher.verify(recent, other), &other_matcher);
  lead.decisive = held_matcher.decisive(lead.distinction, &lead.needed);
  return lead;
}

std::string ISGraphLocalizer::RecentLead::describe() const {
  char need[48];
  std::snprintf(need, sizeof need, ", %.1f m needed", needed);
  return "the recent walls lead for the answer held by " + distinction.describe() + need;
}

bool ISGraphLocalizer::keepAnswer(const MatchInput& input, double stamp) {
  std::string why = floors_.follow(stamp, graph_, answer_);
  bool left_outline = false;
  if (why.empty()) {
    why = agreement_.update(input, graph_, answer_);
    left_outline = agreement_.leftTheOutline();
  }
  if (!why.empty()) {
    lose(stamp, why, left_outline);
    return false;
  }
  releaseDeviatingWalls(
      options_.release_recent_keyframes > 0
          ? recentStretchesOf(input, graph_, R_T_L_, options_.release_recent_keyframes)
          : input,
      stamp, options_.release.strikes);
  if (moveToConsensus(input, stamp)) return false;
  // New S-planes gain correspondences at the current P_T_M; held ones stay as they are, and
  // released ones stay released.
  const Verification now = plan_.verify(input, answer_.P_T_M_x_y_yaw, floors_.level());
  holdWhereAllowed(input, now.planes, false);
  for (const auto& [s, a] : now.rooms) answer_.room_matches.emplace(s, a);
  recaptureRecentWalls(input);
  return true;
}

void ISGraphLocalizer::recaptureRecentWalls(const MatchInput& input) {
  if (options_.recapture_keyframes <= 0 || options_.bend_keyframes > 0 ||
      graph_.keyframes().back().floor < 0) {
    return;
  }
  const MatchInput local = recentPlanesOf(input, graph_, options_.recapture_keyframes);
  if (local.planes.empty()) return;
  double apart = 0.0;
  const std::optional<Eigen::Vector3d> voted = votedMove(local, &apart);
  if (!voted) return;
  const Verification there = plan_.verify(local, *voted, floors_.level());
  holdWhereAllowed(local, there.planes, false);
}

void ISGraphLocalizer::takeStampedStart() {
  // B_T_M from the base's pose at the stamp and the graph's own pose there (the odometry
  // corrected by the last keyframe before it), levelled: the frame the keyframes live in, not the
  // raw odometry's, which the graph may have moved by then.
  const std::optional<Eigen::Isometry3d> M_T_R = graph_.poseAt(stamped_start_->stamp);
  const std::optional<sensors::Odometry> latest = graph_.latestPose();
  if (!M_T_R && !latest) return;
  const Eigen::Isometry3d& at = M_T_R ? *M_T_R : latest->M_T_R;
  const Eigen::Vector3d& B_T_R = stamped_start_->B_T_R;
  const Eigen::Isometry2d B_T_R2 =
      Eigen::Translation2d(B_T_R.head<2>()) * Eigen::Rotation2Dd(B_T_R.z());
  const Eigen::Isometry2d M_T_R2 = Eigen::Translation2d(at.translation().head<2>()) *
                                   Eigen::Rotation2Dd(common::yawOf(at.linear()));
  const Eigen::Isometry2d B_T_M2 = B_T_R2 * M_T_R2.inverse();
  given_start_ = Eigen::Vector3d(B_T_M2.translation().x(), B_T_M2.translation().y(),
                                 Eigen::Rotation2Dd(B_T_M2.linear()).angle());
  stamped_start_.reset();
}

void ISGraphLocalizer::onKeyframe(double stamp) {
  if (stamped_start_) {
    if (stamp < stamped_start_->stamp) return;  // the start is given later: no match before it
    takeStampedStart();
  }
  if (given_start_) {
    const Eigen::Vector3d start = *given_start_;
    given_start_.reset();
    assumeMatch(stamp, start, "the start pose given");
    return;
  }
  const int keyframes = int(graph_.keyframes().size());
  // A new segment starts counting again.
  if (keyframes < keyframes_at_last_bend_) keyframes_at_last_bend_ = 0;
  if (answer_.localized && options_.bend_keyframes > 0 &&
      keyframes - keyframes_at_last_bend_ >= options_.bend_keyframes) {
    bendMapOntoPlan(stamp);
  }
  MatchInput input = matchInput();
  if (answer_.localized) {
    if (!keepAnswer(input, stamp)) return;
  } else if (keyframes > 1 && graph_.keyframes().back().onFloor() &&
             graph_.keyframes().back().registration.attempted &&
             !graph_.keyframes().back().registration.agrees) {
    // Not localized, and the world stopped agreeing with the map: the map so far would mislead
    // the matcher. Start again from here.
    graph_.startNewSegment(stamp, "the scan does not agree with the recent map");
    outside_answer_.reset();
    rooms_at_last_attempt_ = 0;
    keyframes_at_last_attempt_ = 0;
    return;
  }
  if (!answer_.localized && waitingOutside()) return;
  const bool new_rooms = input.rooms.size() != rooms_at_last_attempt_;
  const bool due =
      !answer_.localized && keyframes - keyframes_at_last_attempt_ >= options_.retry_keyframes;
  if (!new_rooms && !due) return;
  rooms_at_last_attempt_ = input.rooms.size();
  keyframes_at_last_attempt_ = keyframes;
  if (answer_.localized) {
    const std::size_t rooms = input.rooms.size();
    const bool check =
        int(rooms) <= options_.contradiction_every_room || rooms < rooms_at_last_check_ ||
        double(rooms) >= double(rooms_at_last_check_) * (1.0 + options_.contradiction_growth);
    if (check) {
      rooms_at_last_check_ = rooms;
      const auto start = std::chrono::steady_clock::now();
      checkForContradiction(stamp);
      contradiction_s_ +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    return;
  }
  int level = -1;
  MatchResult result = plan_.match(input, &level, graph_.pool());
  log_.attempted(result.translated(plan_.B_t_P()));
  record(stamp, result.status, result.reason);
  if (result.status != MatchStatus::kMatched) return;
  adopt(result.best, level);
  refineAnswer(input, stamp);
}

void ISGraphLocalizer::holdWhereAllowed(const MatchInput& input,
                                        const std::vector<std::pair<int, int>>& found,
                                        bool replace) {
  std::map<int, const MatchPlane*> by_id;
  for (const MatchPlane& plane : input.planes) by_id[plane.id] = &plane;
  for (const auto& [plane, surface] : found) {
    const auto seen = by_id.find(plane);
    if (seen == by_id.end()) continue;  // verified on `input`: not reached
    const MatchPlane& p = *seen->second;
    if (!released_.allows(plane, surface, answer_.inP(p.start), answer_.inP(p.end))) continue;
    if (replace) {
      answer_.plane_matches[plane] = surface;
    } else {
      answer_.plane_matches.emplace(plane, surface);
    }
  }
}

void ISGraphLocalizer::releaseDeviatingWalls(const MatchInput& input, double stamp, int strikes) {
  std::vector<std::pair<int, int>> held;  // (S-plane, A-surface) of each of the walls
  const std::vector<HeldWall> walls = heldWalls(answer_, input, graph_, plan_.agraph(), &held);
  released_.judge(walls, held, stamp, strikes, answer_.plane_matches);
}

bool ISGraphLocalizer::moveToConsensus(const MatchInput& input, double stamp) {
  // Only new walls can change the vote; and only on a floor (between floors, the planes mapped
  // from the flight are not yet of any level).
  if (input.planes.size() == planes_at_last_vote_ || graph_.keyframes().back().floor < 0) {
    return false;
  }
  if (options_.bend_keyframes > 0) return false;  // the bends move B_T_M (bend_keyframes)
  planes_at_last_vote_ = input.planes.size();
  // The vote on the level's own matcher; the answers verified again with their indices into the
  // whole A-Graph (CompiledPlan::verify), which the correspondences hold.
  double apart = 0.0;
  const std::optional<Eigen::Vector3d> voted = votedMove(input, &apart);
  if (!voted) return false;
  const Verification moved = plan_.verify(input, *voted, floors_.level());
  const GraphMatcher& matcher = plan_.matcherOf(floors_.level());
  if (options_.move_hold_share > 0.0) {
    // A floor-wide move must not lose where the robot is (move_hold_share).
    const MatchInput recent =
        recentSightingsOf(graph_, R_T_L_, options_.contradiction_recent_keyframes,
                          options_.sgraph.rooms.min_wall_height);
    const double held_here = matcher.wallsAgreeing(recent, answer_.P_T_M_x_y_yaw);
    const double moved_here = matcher.wallsAgreeing(recent, moved.x_y_yaw);
    if (moved_here < options_.move_hold_share * held_here && held_here - moved_here >= 1.0) {
      log_.moveRefused();
      return false;
    }
  }
  log_.moved({stamp, apart, matcher.wallsAgreeing(input, answer_.P_T_M_x_y_yaw),
              matcher.wallsAgreeing(input, *voted)});
  // The vote was taken on the S-Graph as merged, so the move is made on it; every keyframe is
  // re-optimised under the new correspondences below. Only where in the plane, and only this
  // floor's correspondences: the level, the height and the other floors' walls stay.
  // What this floor's walls were judged under the old answer no longer holds: its releases are
  // undone (the log keeps them).
  released_.reopen(input.planes);
  answer_.P_T_M_x_y_yaw = moved.x_y_yaw;
  for (const MatchPlane& plane : input.planes) answer_.plane_matches.erase(plane.id);
  for (const MatchRoom& room : input.rooms) answer_.room_matches.erase(room.id);
  holdWhereAllowed(input, moved.planes, true);
  for (const auto& [s, a] : moved.rooms) answer_.room_matches[s] = a;
  // Not judged again at once, as a new answer's walls are (refineAnswer): the map was merged under
  // the old answer, and in a long building it bent with it; the walls it left off their surfaces
  // are judged on the usual streak of keyframes once the merge has worked under the new answer.
  // Nor are the surfaces the old answer sat on and the new one leaves released: far from the
  // robot, drift rather than the building may put them off (measured, docs/matching.md).
  refitAnswer(input);
  graph_.optimiseAll(true);
  return true;
}

std::optional<Eigen::Vector3d> ISGraphLocalizer::votedMove(const MatchInput& planes,
                                                           double* apart) const {
  const GraphMatcher& matcher = plan_.matcherOf(floors_.level());
  const Eigen::Vector3d voted =
      matcher.consensus(planes, matcher.verify(planes, answer_.P_T_M_x_y_yaw)).x_y_yaw;
  const Eigen::Vector2d middle = GraphMatcher::middleOf(planes);
  *apart = (HeldAnswer::applyPlanar(voted, middle) - answer_.inP(middle)).norm();
  if (*apart < options_.min_answer_move) return std::nullopt;
  return voted;
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
  const auto correction =
      correctionOfAll(heldWalls(answer_, input, graph_, plan_.agraph(), nullptr), options_.release);
  if (!correction) return;
  const Eigen::Rotation2Dd turn(correction->z());
  Eigen::Vector3d& P_T_M = answer_.P_T_M_x_y_yaw;
  P_T_M.head<2>() = turn * P_T_M.head<2>() + correction->head<2>();
  P_T_M.z() += correction->z();
}

nlohmann::json ISGraphLocalizer::graph() const {
  nlohmann::json out = graph_.toJson();
  out["method"] = name();
  out["matching"] =
      matchingJson({plan_, answer_, log_, released_, floors_, merger_.windowsWithAnswerHeld(),
                    merger_.jambFactors(), int(bends_.size())});
  return out;
}

}  // namespace isg::slam
