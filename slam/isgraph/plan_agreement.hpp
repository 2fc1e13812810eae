#pragma once

#include <deque>
#include <string>

#include "slam/isgraph/compiled_plan.hpp"
#include "slam/isgraph/held_answer.hpp"
#include "slam/sgraph/sgraph.hpp"

namespace isg::slam {

// Whether a localized graph still agrees with the world and the plan, keyframe by keyframe
// (docs/matching.md, "Lost"): the scan against the recent map and the plan, the pose inside the
// building, and the held correspondences within a loose gate of their surfaces.
class PlanAgreement {
 public:
  struct Options {
    // A held correspondence is kept while its S-plane stays within these of its surface.
    double hold_angle_deg = 20.0;
    double hold_distance = 0.5;  // m
    // Lost: of the held correspondences the latest keyframe observes (at least min_planes),
    // more than this share disagree; or fewer than min_held remain after any left the gate
    // (unconfirmed when none did: too little evidence, not evidence against).
    int lost_min_planes = 3;
    double lost_disagreeing_share = 0.5;
    int lost_min_held = 3;
    // A scan's plan share: its points at wall height within this of a plan surface (m). Lost
    // when the scan disagrees with the recent map (registration share below suspect_share) and
    // its plan share falls below plan_share_drop × the median of the last plan_share_history
    // keyframes'; or when it stays below plan_share_collapse × that median two keyframes in a row.
    double plan_share_distance = 0.2;
    double suspect_share = 0.5;
    double plan_share_drop = 0.5;
    double plan_share_collapse = 0.3;
    int plan_share_history = 10;
  };

  PlanAgreement(const CompiledPlan& plan, const Eigen::Isometry3d& R_T_L, const Options& options)
      : plan_(&plan), R_T_L_(R_T_L), options_(options) {}

  // Takes the latest keyframe into the agreement (its plan share into the history; held
  // correspondences that left the gate are dropped from `answer`) and says why the graph no
  // longer agrees with the world or the plan (the evidence contradicts the answer: lost); empty
  // while it does. Where the plan merely cannot confirm the answer — fewer than lost_min_held
  // correspondences held, none of them ever dropped for leaving the gate — the answer holds and
  // unconfirmed() says why.
  std::string update(const MatchInput& input, const SGraph& graph, HeldAnswer& answer);
  // Why the plan did not confirm the latest keyframe update() took; empty when it did.
  const std::string& unconfirmed() const { return unconfirmed_; }
  // Whether the latest update() lost the answer because the pose left the drawn building while
  // the scan still agreed with the recent map: the map is intact, only the answer is in question
  // (a walk out of what the plan shows, or an answer slid out along a corridor).
  bool leftTheOutline() const { return left_outline_; }
  // Measured under another answer, or none: the history starts again.
  void clear();
  // The latest keyframe's plan share at the answer's pose, or -1 without a cloud.
  double planShare(const SGraph& graph, const HeldAnswer& answer) const;

 private:
  // The scan against the recent map and the plan; why they both disagree, or empty.
  std::string scanDisagreement(const SGraph& graph, const HeldAnswer& answer);
  // The held correspondences' gate; why the plan contradicts what the robot sees, or empty.
  std::string heldDisagreement(const MatchInput& input, const SGraph& graph, HeldAnswer& answer);

  const CompiledPlan* plan_;
  Eigen::Isometry3d R_T_L_;
  Options options_;
  std::deque<double> plan_shares_;  // of the latest localized keyframes
  int plan_collapsed_ = 0;          // keyframes in a row with a collapsed plan share
  int dropped_disagreeing_ = 0;     // held walls that left the gate since the last clear()
  std::string unconfirmed_;
  bool left_outline_ = false;
};

}  // namespace isg::slam
