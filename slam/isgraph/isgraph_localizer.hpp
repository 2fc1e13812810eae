#pragma once

#include <ceres/ceres.h>
#include <numbers>

#include <Eigen/Geometry>
#include <array>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bim/agraph.hpp"
#include "bim/agraph_optimizer.hpp"
#include "bim/plane_manifold.hpp"
#include "slam/isgraph/flight_footprints.hpp"
#include "slam/isgraph/graph_matching.hpp"
#include "slam/isgraph/level_matching.hpp"
#include "slam/isgraph/plan_distance_field.hpp"
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
  // a full match runs again with every new room, on the S-Graph optimised without the plan, to
  // catch a contradiction.
  int retry_keyframes = 1;
  // Once localized, whenever new S-planes are mapped the plan walls are asked whether the answer
  // should move (GraphMatcher::consensus): a move of at least this much is taken; smaller ones
  // are the merge's to make.
  double min_answer_move = 0.05;  // m
  // Holding the plan (docs/matching.md). A correspondence, once made, is kept while its S-plane
  // stays within these of its surface at the current B_T_M: far looser than the matcher's
  // tolerances, so that drift the merge has not yet corrected does not drop it.
  double hold_angle_deg = 20.0;
  double hold_distance = 0.5;  // m
  // An imprecise plan (docs/matching.md): a held wall that disagrees with its planned surface by
  // more than the others explain is released from the merge and not matched again under this
  // answer.
  WallReleaseOptions release;
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

// The S-Graph as the matcher sees it (walls of a minimum height, confirmed rooms, transitions),
// of the floor the robot stands on (the latest one it stood on, while on the stairs).
MatchInput matchInputOf(const SGraph& graph, double min_wall_height);

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
class ISGraphLocalizer : public Localizer {
 public:
  ISGraphLocalizer(const Eigen::Isometry3d& R_T_L, const bim::AGraph& plan,
                   const ISGraphOptions& options = {});
  // It points into its own copy of the plan.
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
  nlohmann::json graph() const override;
  std::optional<std::string> searchStatus() const override { return toString(status_); }
  std::vector<StatusChange> statusChanges() const override;
  std::optional<MapDiagnostics> mapDiagnostics() const override { return graph_.diagnostics(); }
  sensors::StageTimes stageTimes() const override;

  // Takes `x_y_yaw` as B_T_M (in B), as if matched, with the correspondences it implies now: a hint
  // from outside (an operator's initial pose), or a test's wrong first match. It is checked like
  // any match: contradicted by a unique answer elsewhere, or lost.
  void assumeMatch(double stamp, const Eigen::Vector3d& x_y_yaw, const std::string& reason);

  const SGraph& sgraph() const { return graph_; }
  MatchStatus status() const { return status_; }
  const std::vector<StatusChange>& events() const { return events_; }
  // The latest full match, its answers in B.
  const std::optional<MatchResult>& lastMatch() const { return last_match_; }
  // The plan level (index into the A-Graph's floors) of the floor the robot stands on, while
  // localized; -1 otherwise.
  int level() const { return localized_ ? level_ : -1; }
  // Where the robot arrived on a floor while localized: the stamp and the level it is.
  struct LevelChange {
    double stamp = 0.0;
    int floor = -1;  // the S-Graph's
    int level = -1;  // the A-Graph's
  };
  const std::vector<LevelChange>& levelChanges() const { return level_changes_; }
  // The S-Graph as the matcher sees it now.
  MatchInput matchInput() const {
    return matchInputOf(graph_, options_.sgraph.rooms.min_wall_height);
  }
  // Seconds spent in full matching attempts, one entry per attempt.
  const std::vector<double>& matchingTimes() const { return matching_times_; }

 private:
  void onKeyframe(double stamp);
  void record(double stamp, MatchStatus status, const std::string& reason);
  // Takes an answer on plan level `level` (-1: the level of its first matched room) for the
  // floor the robot stands on.
  void adopt(const Verification& answer, int level = -1);
  // One full match of the current floor: against every level when the plan has several.
  MatchResult matchNow(const MatchInput& input, int* level) const;
  // verify() on the current floor's level.
  Verification verifyNow(const MatchInput& input, const Eigen::Vector3d& P_T_M_x_y_yaw) const;
  // While localized, the level of the floor the robot stands on: known, or found from its height
  // above a floor whose level is known. Returns why not, empty when it is known.
  std::string followFloor(double stamp);
  // The plan level at the height of S-floor `floor`, from a floor whose level is known; -1 when
  // no level is within level_tolerance.
  int levelAtHeightOf(int floor) const;
  // Why the latest keyframe, on the stairs, is on none of the current level's flights; empty
  // when it is on one.
  std::string offFlight() const;
  // Takes the latest keyframe into the localized graph's agreement with the world and the plan
  // (the plan-share history, the collapse count; held correspondences that left the hold gate are
  // dropped) and says why the graph no longer agrees; empty while it does.
  std::string updateAgreement(const MatchInput& input);
  // Judges the held walls of the current floor against each other and releases those that
  // disagree with their planned surfaces (WallReleaseOptions) on `strikes` judgements in a row.
  void releaseDeviatingWalls(const MatchInput& input, double stamp, int strikes);
  // The held correspondences of the current floor as the release judges them, in P under the
  // current P_T_M; with their (S-plane, A-surface) in `held` if given.
  std::vector<HeldWall> heldWalls(const MatchInput& input,
                                  std::vector<std::pair<int, int>>* held) const;
  // A new answer: its walls built off the plan released at once, and P_T_M refitted to the rest.
  void refineAnswer(const MatchInput& input, double stamp);
  // P_T_M refitted to the held walls, robustly (correctionOfAll).
  void refitAnswer(const MatchInput& input);
  // When new S-planes were mapped since the last vote: the answer moved to where more plan walls
  // agree (GraphMatcher::consensus), if by min_answer_move or more. True when it moved.
  bool moveToConsensus(const MatchInput& input, double stamp);
  // The latest keyframe's plan agreement (see ISGraphOptions), or -1 without a cloud.
  double planShare() const;
  void lose(double stamp, const std::string& reason);
  // A full match while localized, judged on the S-Graph optimised without the plan.
  void checkForContradiction(double stamp);
  void addPlanFactors(ceres::Problem& problem, const std::set<int>& planes,
                      const std::vector<int>& rooms);
  void addSurface(ceres::Problem& problem, int surface);
  // The S-room's widths, measured through its centre from the map's planes, along the matched
  // plan room's two pairs (in node.pairs order); none unless both are four-wall rooms.
  std::optional<std::array<double, 2>> widthsAlongPlanPairs(int room,
                                                            const bim::RoomNode& node) const;

  // B_T_M in the plane from P_T_M, and back.
  Eigen::Vector3d inB(const Eigen::Vector3d& P_T_M_x_y_yaw) const;
  Eigen::Vector3d inP(const Eigen::Vector3d& B_T_M_x_y_yaw) const;

  ISGraphOptions options_;
  Eigen::Vector2d B_t_P_;    // P's origin in B: B_T_P is this translation
  bim::AGraph plan_in_P_;    // the plan's A-Graph moved into P
  const bim::AGraph* plan_;  // = &plan_in_P_
  Eigen::Isometry3d R_T_L_;
  PlanDistanceField plan_field_;
  std::deque<double> plan_shares_;  // of the latest localized keyframes
  int plan_collapsed_ = 0;          // keyframes in a row with a collapsed plan share
  SGraph graph_;
  GraphMatcher matcher_;
  // With several levels: each level's A-Graph matched on its own, the answers compared.
  std::unique_ptr<LevelMatcher> level_matcher_;
  std::vector<FlightFootprint> flights_;  // in P
  std::map<int, int> floor_levels_;       // S-Graph floor → A-Graph floor, while localized
  int level_ = -1;                        // of the current floor, while localized
  std::vector<LevelChange> level_changes_;
  bim::AGraphState plan_state_;
  bim::PlaneManifold plane_manifold_;
  ceres::HuberLoss huber_{1.0};

  MatchStatus status_ = MatchStatus::kNotYet;
  bool localized_ = false;
  // P_T_M in the plane (x, y, yaw; the merging optimises these three) and its height, which the
  // floors give (P and B share z): mapInPlan() makes B_T_P · P_T_M of the two.
  Eigen::Vector3d P_T_M_x_y_yaw_ = Eigen::Vector3d::Zero();
  double P_T_M_z_ = 0.0;
  bool z_from_floor_ = false;  // P_T_M_z_ from a floor plane seen (not yet: as if at height 0)
  std::map<int, int> plane_matches_;  // S-plane → A-surface
  std::map<int, int> room_matches_;   // S-room → A-room
  // Walls released under the answer held now: never matched again under it.
  struct ReleasedWall {
    double stamp = 0.0;
    int plane = -1;                    // S-plane
    int surface = -1;                  // A-surface
    double offset = 0.0, angle = 0.0;  // the residual that released it (m, rad)
  };
  std::vector<ReleasedWall> released_;  // in the order released, for the log
  std::set<int> released_planes_;       // the same, to look up
  // Released A-surface → the offset along its normal that released it (the latest): how far the
  // wall stands off the plan, which moves its rooms' centres by half as much.
  std::map<int, double> released_surfaces_;
  std::map<int, int> release_strikes_;     // S-plane → keyframes in a row beyond a threshold
  std::optional<MatchResult> last_match_;  // in B
  std::vector<StatusChange> events_;
  std::vector<double> matching_times_;
  double matching_s_ = 0.0;  // onKeyframe in all: matching, verification, contradictions
  std::size_t rooms_at_last_attempt_ = 0;
  int keyframes_at_last_attempt_ = 0;
  std::set<int> surfaces_in_problem_;  // per optimisation
  Eigen::AlignedBox2d building_;       // the plan's walls' box grown by outside_margin, in P
  int contradictions_ = 0;
  struct AnswerMove {  // moved to where more plan walls agree (moveToConsensus)
    double stamp = 0.0;
    double distance = 0.0;                         // m, at the middle of the map
    double walls_before = 0.0, walls_after = 0.0;  // GraphMatcher::wallsAgreeing
  };
  std::vector<AnswerMove> answer_moves_;
  std::size_t planes_at_last_vote_ = 0;
  int losses_ = 0;
  int held_constant_ = 0;  // optimisations in which B_T_M was held (under-constrained)
};

}  // namespace isg::slam
