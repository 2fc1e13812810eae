#pragma once

#include <Eigen/Geometry>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "bim/agraph.hpp"
#include "bim/optimizer/agraph_optimizer.hpp"
#include "slam/isgraph/compiled_plan.hpp"
#include "slam/isgraph/floor_following.hpp"
#include "slam/isgraph/graph_matching.hpp"
#include "slam/isgraph/held_answer.hpp"
#include "slam/isgraph/match_input.hpp"
#include "slam/isgraph/match_log.hpp"
#include "slam/isgraph/plan_agreement.hpp"
#include "slam/isgraph/plan_merging.hpp"
#include "slam/isgraph/released_walls.hpp"
#include "slam/isgraph/wall_release.hpp"
#include "slam/localizer.hpp"
#include "slam/sgraph/sgraph.hpp"

namespace isg::slam {

struct ISGraphOptions {
  SGraphOptions sgraph;
  MatchingOptions matching;
  bim::AGraphSigmas plan;  // the A-Graph's own factors and plane priors
  // Merging factors. Plane-to-plane is robust (Huber): as built, a wall may stand a few
  // centimetres from where the plan draws it.
  double sigma_plane_angle = 2.0 * std::numbers::pi / 180.0;
  double sigma_plane_distance = 0.04;
  double sigma_room = 0.1;
  // While not localized, matching is tried again after a new room is confirmed or after this
  // many keyframes: every keyframe, because what decides between two answers is often not a new
  // room but a wall or a room's size settling, and an attempt costs milliseconds
  // (docs/matching.md). Once localized, new S-planes gain correspondences as they are mapped and
  // a full match runs again on the S-Graph optimised without the plan, to catch a contradiction:
  // with every new room up to `contradiction_every_room` S-rooms, then each time the S-rooms have
  // grown by `contradiction_growth` since the last check. Each check costs the whole map against
  // the whole plan; spaced geometrically, their sum stays a few times the last one's instead of
  // growing with the square of the rooms (a 200-room floor: 0.6 s a check by its 35th room).
  int retry_keyframes = 1;
  int contradiction_every_room = 20;
  double contradiction_growth = 0.1;
  // A contradiction must hold where the robot is: the walls the latest
  // `contradiction_recent_keyframes` keyframes saw are matched under both answers, and when they
  // lead for the answer held as decisively as a match must lead, the new answer is refused. On a
  // floor of a hundred metres the map bends with the odometry's drift (a metre and more), and the
  // one rigid transform that fits the most of it is a compromise that fits where the robot is
  // worst; a first match made wrong by symmetry is alike or worse on the recent walls, and still
  // contradicted (docs/matching.md, "A contradiction must hold where the robot is"). 0 leaves it
  // out.
  int contradiction_recent_keyframes = 25;
  // The merged graph bends (docs/matching.md, "The merged graph bends"): while localized, every
  // `bend_keyframes` keyframes — and at the next keyframe after a contradiction was refused —
  // every keyframe, wall and room of the segment is optimised at once with the plan's
  // correspondences held (SGraph::optimiseAll with the merge), so that the map mapped long before
  // follows the plan rather than the drift it was mapped with; the window moves only the latest
  // keyframes. While the map bends, `B_T_M` moves with the bends and the windows only: neither the
  // floor-wide vote (min_answer_move) nor the recent walls' vote (recapture_keyframes) runs. On
  // floors of 1000 offices the first moved the answer toward a rigid compromise of the bent map,
  // 0.3–1.5 m off, and the second, its correspondences made at its own answer, let a map slide
  // 1.5 m along a corridor (docs/matching.md, "The merged graph bends"). 0 leaves the bends out,
  // and the votes run.
  int bend_keyframes = 25;
  // Without the bends (bend_keyframes 0): a floor-wide move of the answer (min_answer_move) is
  // refused when the walls the latest
  // `contradiction_recent_keyframes` keyframes saw (recentSightingsOf) agree with it less than
  // this share as well as with the answer held, and by a wall or more
  // (GraphMatcher::wallsAgreeing): the whole bent map's vote must not take the answer from where
  // the robot is. Not tighter: the sightings were placed under the answer held, so a right move
  // loses a little of their agreement too. 0 leaves it out.
  double move_hold_share = 0.5;
  // Without the bends (bend_keyframes 0), once localized, whenever new S-planes are mapped the
  // plan walls are asked whether the answer should move (GraphMatcher::consensus): a move of at
  // least this much is taken; smaller ones are the merge's to make.
  double min_answer_move = 0.05;  // m
  // Along a corridor the window's walls may all face one way, and the merge then cannot hold the
  // map along it: drift moves the recent map past the matcher's distance from the walls that
  // would (a partition seen through a door), and they are never matched. So the walls the latest
  // `recapture_keyframes` keyframes saw vote among themselves too (GraphMatcher::consensus on
  // them alone), and those the local vote puts on a surface gain that correspondence; the merge
  // then pulls the map there. 0 leaves it out; so do the bends (bend_keyframes), whose door jambs
  // and whole-map optimisation hold the map along the corridor instead.
  int recapture_keyframes = 25;
  // Door jambs seen from keyframes tie them to the plan along the wall (docs/matching.md).
  JambOptions jambs;
  // Holding the plan (docs/matching.md). A correspondence, once made, is kept while its S-plane
  // stays within these of its surface at the current B_T_M: far looser than the matcher's
  // tolerances, so that drift the merge has not yet corrected does not drop it.
  double hold_angle_deg = 20.0;
  double hold_distance = 0.5;  // m
  // An imprecise plan (docs/matching.md): a held wall that disagrees with its planned surface by
  // more than the others explain is released from the merge, and its surface is not matched
  // again under this answer along the stretch it was seen off (ReleasedWalls).
  WallReleaseOptions release;
  // Once localized, the walls the latest `release_recent_keyframes` keyframes saw are judged for
  // release where they saw them (recentStretchesOf), each against the correction of the others
  // among them: on a floor whose map bends, one rigid correction of every wall of the floor
  // leaves the far walls' bend as their "deviation" (1000-office floors as built logged 520–2342
  // releases in 20 minutes; judged among the recent walls, 101–235; judged where they were seen,
  // with the S-Graph's walls in pieces of at most 40 m, 12–57), and a wall released is no longer
  // bent back onto the plan. A new answer's first judgement (refineAnswer) takes every wall
  // whole. 0 judges every wall of the floor, whole, each time.
  int release_recent_keyframes = 25;
  // Lost: of the held correspondences the latest keyframe observes (at least lost_min_planes),
  // more than this share disagree; or fewer than lost_min_held remain in the segment.
  int lost_min_planes = 3;
  double lost_disagreeing_share = 0.5;
  int lost_min_held = 3;
  // Lost: the pose in B further than this outside the box of the plan's walls on the level.
  double outside_margin = 1.0;  // m
  // B_T_M is never free: a weak prior at its value before each optimisation, and held constant
  // when the window's correspondences do not fix it (surface normals not spanning two directions
  // at least this far apart, and no matched four-wall room).
  double sigma_B_T_M_translation = 0.5;                     // m
  double sigma_B_T_M_yaw = 5.0 * std::numbers::pi / 180.0;  // rad
  double min_normal_spread_deg = 30.0;
  // Plan agreement of a keyframe's scan: the share of its points at wall height (−0.4 … +1.2 m
  // about the sensor) within plan_share_distance of a plan surface, at the pose in B. Lost when
  // the scan disagrees with the recent map (registration share below suspect_share) and its plan
  // share falls below plan_share_drop × the median of the last keyframes'; or when the plan share
  // stays below plan_share_collapse × that median for two keyframes in a row.
  double plan_share_distance = 0.2;  // m
  double suspect_share = 0.5;
  double plan_share_drop = 0.5;
  double plan_share_collapse = 0.3;
  int plan_share_history = 10;
  // Several storeys (docs/matching.md): once localized, a floor the robot reaches is the level
  // at the elevation its height above the matched floor leads to, within this; none there → lost.
  // Half the least storey height (2 m of headroom, docs/formats.md).
  double level_tolerance = 1.0;  // m
  // The robot changes floor only on a flight of stairs: once localized, a keyframe on the stairs
  // (between floors) farther than this from every flight of the plan that joins the current
  // level means the match is wrong (lost). It covers the pose error and a flight's ends, where
  // the robot starts rising: a pose on a flight is inside its rectangle.
  double flight_margin = 1.0;  // m
};

// The iS-Graph (paper §IV–V): the S-Graph, matched against the plan's A-Graph, then merged with
// it. Until the match is unique it localizes in M only; from then on B_T_M is part of every
// window optimisation, with plane-to-plane and room-to-room factors and the A-Graph's own wall
// and room factors and plane priors, and its pose in B is B_T_M · M_T_R.
//
// Inside, the plan is held in its local frame P: B moved so that its origin is the middle of the
// plan's walls (AGraph::localOrigin). A plane's d and the factors' closest points are measured
// from the frame's origin, so in B a model kilometres from its origin would couple every wall's
// angle to its position by that lever arm (docs/conventions.md, "Where B's origin is"). Matching
// and merging estimate P_T_M; everything that leaves the localizer is in B.
//
// It is made of parts, each with its own tests: what the plan gives once (CompiledPlan), the
// answer held (HeldAnswer), the log of the matching (MatchLog), the walls released from the merge
// (ReleasedWalls), the floors followed (FloorFollower), the checks that the answer still holds
// (PlanAgreement) and the merge's factors (PlanMerger); its sgraph.json part is isgraph_json's.
// This class decides, keyframe by keyframe, when each acts.
class ISGraphLocalizer : public Localizer {
 public:
  ISGraphLocalizer(const Eigen::Isometry3d& R_T_L, const bim::AGraph& plan,
                   const ISGraphOptions& options = {});
  // Its parts point into its own compiled plan and answer.
  ISGraphLocalizer(const ISGraphLocalizer&) = delete;
  ISGraphLocalizer& operator=(const ISGraphLocalizer&) = delete;

  std::string name() const override { return "is-graphs"; }
  void pushOdometry(const sensors::Odometry& odometry) override { graph_.addOdometry(odometry); }
  void pushImu(const sensors::ImuSample& sample) override { graph_.addImu(sample); }
  void setImuMount(const Eigen::Isometry3d& R_T_I) { graph_.setImuMount(R_T_I); }
  void pushScan(const sensors::Scan& scan) override;
  bool wantsScan(double stamp) const override;
  std::optional<sensors::Odometry> poseInMap() const override { return graph_.latestPose(); }
  std::optional<Eigen::Isometry3d> mapInPlan() const override;
  // Whether the latest keyframe agreed with the plan (PlanAgreement::unconfirmed) and a keyframe
  // of the window the merge optimises (the latest SGraphOptions::window) sees a wall tied to a
  // plan surface: without one, nothing holds the recent map to the plan.
  bool planConfirms() const override;
  nlohmann::json graph() const override;
  std::optional<std::string> searchStatus() const override { return toString(log_.status()); }
  std::vector<StatusChange> statusChanges() const override { return log_.events(); }
  std::optional<MapDiagnostics> mapDiagnostics() const override { return graph_.diagnostics(); }
  sensors::StageTimes stageTimes() const override;

  // Takes `x_y_yaw` as B_T_M (in B), as if matched, with the correspondences it implies now: a hint
  // from outside (an operator's initial pose), or a test's wrong first match. It is checked like
  // any match: contradicted by a unique answer elsewhere, or lost.
  void assumeMatch(double stamp, const Eigen::Vector3d& x_y_yaw, const std::string& reason);
  // The start pose given from outside (isg run --start-pose; the Hilti challenge gives every
  // run's first pose): `B_T_M` as (x, y, yaw) in B, taken at the first keyframe as assumeMatch
  // takes a hint, and checked like any match from then on.
  void giveStart(const Eigen::Vector3d& B_T_M_x_y_yaw) { given_start_ = B_T_M_x_y_yaw; }
  // The start pose given as the base's pose in B at a later `stamp` (the floor-plan benchmark gives
  // each run's pose about 5 s after it starts): at the first scan from that stamp on, the graph's
  // own pose at the stamp makes it B_T_M, taken as giveStart's. Until then no match is tried: the
  // run starts localized there, as asked.
  void giveStartAt(double stamp, const Eigen::Vector3d& B_T_R_x_y_yaw) {
    stamped_start_ = StampedStart{stamp, B_T_R_x_y_yaw};
  }

  const SGraph& sgraph() const { return graph_; }
  MatchStatus status() const { return log_.status(); }
  const std::vector<StatusChange>& events() const { return log_.events(); }
  // The latest full match, its answers in B.
  const std::optional<MatchResult>& lastMatch() const { return log_.lastMatch(); }
  // The plan level (index into the A-Graph's floors) of the floor the robot stands on, while
  // localized; -1 otherwise.
  int level() const { return answer_.localized ? floors_.level() : -1; }
  // Where the robot arrived on a floor while localized: the stamp and the level it is.
  using LevelChange = FloorFollower::LevelChange;
  const std::vector<LevelChange>& levelChanges() const { return floors_.changes(); }
  // The S-Graph as the matcher sees it now.
  MatchInput matchInput() const {
    return matchInputOf(graph_, options_.sgraph.rooms.min_wall_height);
  }
  // Seconds spent in full matching attempts, one entry per attempt.
  const std::vector<double>& matchingTimes() const { return log_.matchingTimes(); }
  // Each whole-map bend (ISGraphOptions::bend_keyframes): when, on how large a map, how long.
  struct MapBend {
    double stamp = 0.0;
    int keyframes = 0;  // of the segment
    int rooms = 0;      // confirmed S-rooms
    double seconds = 0.0;
  };
  const std::vector<MapBend>& bends() const { return bends_; }

 private:
  void onKeyframe(double stamp);
  // While localized: the floor followed, the agreement checked (lost otherwise), walls judged,
  // the answer moved by the walls' vote, new correspondences made. False when it lost the answer
  // or moved it (nothing more this keyframe).
  bool keepAnswer(const MatchInput& input, double stamp);
  void record(double stamp, MatchStatus status, const std::string& reason);
  // Takes an answer on plan level `level` (-1: the level of its first matched room) for the
  // floor the robot stands on.
  void adopt(const Verification& answer, int level = -1);
  // A new answer: its walls built off the plan released at once, and P_T_M refitted to the rest.
  void refineAnswer(const MatchInput& input, double stamp);
  // P_T_M refitted to the held walls, robustly (correctionOfAll).
  void refitAnswer(const MatchInput& input);
  // Adds the correspondences `found` (S-planes of `input`) to the answer where the releases allow
  // them, each S-plane placed in P by the answer held; `replace`: over a correspondence held.
  void holdWhereAllowed(const MatchInput& input, const std::vector<std::pair<int, int>>& found,
                        bool replace);
  // The held walls of the current floor judged against each other (ReleasedWalls).
  void releaseDeviatingWalls(const MatchInput& input, double stamp, int strikes);
  // When new S-planes were mapped since the last vote: the answer moved to where more plan walls
  // agree (GraphMatcher::consensus), if by min_answer_move or more. True when it moved.
  bool moveToConsensus(const MatchInput& input, double stamp);
  // The latest keyframe's points that may lie on door jambs, kept for the merge's windows.
  void noteJambs();
  // The recent walls' own vote (recapture_keyframes): correspondences for those it places.
  void recaptureRecentWalls(const MatchInput& input);
  // Where the planes' vote on the level's matcher puts P_T_M (GraphMatcher::consensus), if that
  // moves the planes' middle by min_answer_move or more; `apart` gets the move.
  std::optional<Eigen::Vector3d> votedMove(const MatchInput& planes, double* apart) const;
  // Lets the answer go; the S-Graph starts a fresh segment unless `keep_map` (the map is intact:
  // the pose left the drawn building while the scan agreed with the recent map).
  void lose(double stamp, const std::string& reason, bool keep_map = false);
  // While the answer let go on leaving the drawn building would still put the robot outside it
  // (up to kOutsideWaitKeyframes): no match is tried, so that none is adopted and lost again at
  // every keyframe beyond the plan.
  bool waitingOutside();
  // A full match while localized, judged on the S-Graph optimised without the plan.
  void checkForContradiction(double stamp);
  // Every keyframe, wall and room of the segment optimised at once with the merge (bend_keyframes).
  void bendMapOntoPlan(double stamp);
  // What the latest keyframes' sightings of walls, as the robot holds them (recentSightingsOf),
  // say for the answer held against `other` (on `other_level`); none when there are none
  // (contradiction_recent_keyframes).
  struct RecentLead {
    Distinction distinction;  // the answer held's lead (negative: the other's)
    double needed = 0.0;      // m of evidence a decisive lead needs
    bool decisive = false;
    std::string describe() const;
  };
  std::optional<RecentLead> recentLeadForHeld(const Eigen::Vector3d& other, int other_level) const;

  ISGraphOptions options_;
  Eigen::Isometry3d R_T_L_;
  CompiledPlan plan_;  // in P
  SGraph graph_;
  HeldAnswer answer_;
  MatchLog log_;
  ReleasedWalls released_;
  FloorFollower floors_;
  PlanAgreement agreement_;
  PlanMerger merger_;
  // When matching is tried again (retry_keyframes, new rooms) and the walls vote (new planes).
  std::size_t rooms_at_last_attempt_ = 0;
  std::size_t rooms_at_last_check_ = 0;  // S-rooms at the last contradiction check
  int keyframes_at_last_attempt_ = 0;
  int keyframes_at_last_bend_ = 0;
  std::vector<MapBend> bends_;
  double bend_s_ = 0.0;                         // of matching_s_, the whole-map bends
  std::optional<Eigen::Vector3d> given_start_;  // until the first keyframe takes it
  struct StampedStart {
    double stamp = 0.0;
    Eigen::Vector3d B_T_R = Eigen::Vector3d::Zero();  // x, y, yaw
  };
  std::optional<StampedStart> stamped_start_;  // until a scan reaches its stamp
  void takeStampedStart();                     // makes it given_start_
  // P_T_M of the answer let go when the pose left the drawn building with the map intact, and
  // the keyframes since (waitingOutside).
  std::optional<Eigen::Vector3d> outside_answer_;
  int outside_keyframes_ = 0;
  std::size_t planes_at_last_vote_ = 0;
  double matching_s_ = 0.0;       // onKeyframe in all: matching, verification, contradictions
  double contradiction_s_ = 0.0;  // of which the contradiction checks
  double jambs_s_ = 0.0;          // gathering the keyframes' door jamb points
};

}  // namespace isg::slam
