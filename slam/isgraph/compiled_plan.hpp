#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "bim/agraph.hpp"
#include "slam/isgraph/flight_footprints.hpp"
#include "slam/isgraph/graph_matching.hpp"
#include "slam/isgraph/level_matching.hpp"
#include "slam/isgraph/plan_distance_field.hpp"

namespace isg::slam {

// What the plan gives the iS-Graph once, before any scan, and never changes: the A-Graph moved
// into the frame P (B with its origin moved to the middle of the plan's walls, so that a plane's
// d is never measured across kilometres: docs/conventions.md, "Where B's origin is"), the
// distance field scans are checked against, the flights' footprints, the box a pose must stay
// in, and the matchers over the whole plan and each of its levels. A run's state is elsewhere
// (HeldAnswer and the localizer's parts); this is what a run, or many, are given.
class CompiledPlan {
 public:
  // `outside_margin`: how far outside the box of the plan's walls a pose may lie (m).
  CompiledPlan(const bim::AGraph& plan, const MatchingOptions& matching, double outside_margin);
  // The matchers point into its own A-Graph.
  CompiledPlan(const CompiledPlan&) = delete;
  CompiledPlan& operator=(const CompiledPlan&) = delete;

  // The A-Graph in P.
  const bim::AGraph& agraph() const { return plan_in_P_; }
  // P's origin in B: B_T_P is this translation.
  const Eigen::Vector2d& B_t_P() const { return B_t_P_; }
  // A planar pose (x, y, yaw) of M in P as one in B, and back.
  Eigen::Vector3d inB(const Eigen::Vector3d& P_T_M_x_y_yaw) const;
  Eigen::Vector3d inP(const Eigen::Vector3d& B_T_M_x_y_yaw) const;

  const PlanDistanceField& distanceField() const { return field_; }
  // In P; none with one level.
  const std::vector<FlightFootprint>& flights() const { return flights_; }
  // The box of the plan's walls grown by the outside margin, in P.
  const Eigen::AlignedBox2d& building() const { return building_; }

  bool severalLevels() const { return level_matcher_ != nullptr; }
  // The matcher of the whole plan.
  const GraphMatcher& matcher() const { return matcher_; }
  // The matcher of one level (with one level, the whole plan's).
  const GraphMatcher& matcherOf(int level) const;
  // One full match: against every level when the plan has several (`level` gets the best's;
  // -1 with one level).
  MatchResult match(const MatchInput& input, int* level, ThreadPool* pool = nullptr) const;
  // GraphMatcher::verify on `level` (ignored with one level), indices into the whole A-Graph.
  Verification verify(const MatchInput& input, const Eigen::Vector3d& P_T_M_x_y_yaw,
                      int level) const;
  // The best verification of a pose over the levels, and its level (-1 with one level).
  Verification verifyOnBestLevel(const MatchInput& input, const Eigen::Vector3d& P_T_M_x_y_yaw,
                                 int* level) const;

 private:
  Eigen::Vector2d B_t_P_;
  bim::AGraph plan_in_P_;
  PlanDistanceField field_;
  GraphMatcher matcher_;
  std::unique_ptr<LevelMatcher> level_matcher_;
  std::vector<FlightFootprint> flights_;
  Eigen::AlignedBox2d building_;
};

}  // namespace isg::slam
