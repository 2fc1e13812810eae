#pragma once

#include <ceres/ceres.h>

#include <array>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <vector>

#include "bim/optimizer/agraph_optimizer.hpp"
#include "bim/optimizer/plane_manifold.hpp"
#include "slam/isgraph/compiled_plan.hpp"
#include "slam/isgraph/door_jambs.hpp"
#include "slam/isgraph/held_answer.hpp"
#include "slam/isgraph/released_walls.hpp"
#include "slam/sgraph/sgraph.hpp"

namespace isg::slam {

// Graph merging (paper §V): while localized, every window of the S-Graph's optimisation holds
// P_T_M and the plan's part that its planes and rooms are matched to — plane-to-plane and
// room-to-room factors, the A-Graph's own wall and room factors and its surfaces' priors — so
// that the plan sharpens the map and the map places itself in the plan.
class PlanMerger {
 public:
  struct Options {
    bim::AGraphSigmas plan;  // the A-Graph's own factors and plane priors
    // Plane-to-plane is robust (Huber): as built, a wall may stand a few centimetres from where
    // the plan draws it.
    double sigma_plane_angle = 2.0 * std::numbers::pi / 180.0;
    double sigma_plane_distance = 0.04;
    double sigma_room = 0.1;
    // P_T_M is never free: a weak prior at its value before each optimisation, and held
    // constant when the window's correspondences do not fix it (surface normals not spanning
    // two directions at least min_normal_spread_deg apart, and no matched four-wall room).
    double sigma_B_T_M_translation = 0.5;                     // m
    double sigma_B_T_M_yaw = 5.0 * std::numbers::pi / 180.0;  // rad
    double min_normal_spread_deg = 30.0;
    // Door jambs seen from the window's keyframes (door_jambs.hpp).
    JambOptions jambs;
  };

  PlanMerger(const CompiledPlan& plan, const Options& options)
      : plan_(&plan),
        options_(options),
        state_(plan.agraph()),
        jambs_(plan.agraph(), options.jambs) {}
  // The problem holds pointers into its state.
  PlanMerger(const PlanMerger&) = delete;
  PlanMerger& operator=(const PlanMerger&) = delete;

  // Adds the merge's factors for a window of `planes` and `rooms` (SGraph's window hook): nothing
  // unless the answer is held. P_T_M's data, the S-planes' and the S-rooms' are blocks of it. The
  // problem must not own loss functions or manifolds: the merger keeps its own (as SGraph's
  // windows are made).
  void addFactors(ceres::Problem& problem, const std::set<int>& planes,
                  const std::vector<int>& rooms, SGraph& graph, HeldAnswer& answer,
                  const ReleasedWalls& released);
  // Keeps the points of keyframe `keyframe`'s scan (in L; the keyframe's pose in P and the
  // sensor's mount given) that may lie on a door jamb, for the windows it will be in; forgets
  // those of keyframes before `keep_from`.
  void noteKeyframe(int keyframe, const sensors::Scan& scan, const Eigen::Isometry3d& P_T_R,
                    const Eigen::Isometry3d& R_T_L, int keep_from);
  // Forgets every keyframe's jamb points: a new segment or a new answer.
  void forgetKeyframes() { sightings_.clear(); }
  // Jamb factors added over the run.
  long jambFactors() const { return jamb_factors_; }
  // Windows in which P_T_M was held constant (under-constrained).
  int windowsWithAnswerHeld() const { return held_constant_; }

 private:
  void addSurface(ceres::Problem& problem, int surface);
  // The room factors of a matched four-wall room: the A-Graph's own, and one tying the S-room's
  // centre to the plan room's along the pairs whose walls stand where the plan has them.
  // Adds to `normals` the direction a room held along one pair fixes; true when it holds both.
  bool addRoomFactors(ceres::Problem& problem, int room, int plan_room, SGraph& graph,
                      HeldAnswer& answer, const ReleasedWalls& released,
                      std::vector<Eigen::Vector2d>& normals);
  // The S-room's widths, measured through its centre from the map's planes, along the matched
  // plan room's two pairs (in node.pairs order); none unless both are four-wall rooms.
  std::optional<std::array<double, 2>> widthsAlongPlanPairs(int room, const bim::RoomNode& node,
                                                            const SGraph& graph,
                                                            const HeldAnswer& answer) const;

  // The jambs seen from the window's free keyframes, each tying its keyframe to P_T_M (those of
  // released walls too: a release judges a wall across itself, a jamb holds the map along it).
  void addJambFactors(ceres::Problem& problem, SGraph& graph, HeldAnswer& answer);

  const CompiledPlan* plan_;
  Options options_;
  bim::AGraphState state_;
  DoorJambs jambs_;
  std::map<int, std::vector<JambSighting>> sightings_;  // by keyframe
  Eigen::Isometry3d R_T_L_ = Eigen::Isometry3d::Identity();
  long jamb_factors_ = 0;
  bim::PlaneManifold plane_manifold_;
  ceres::HuberLoss huber_{1.0};
  std::set<int> surfaces_in_problem_;  // per optimisation
  int held_constant_ = 0;
};

}  // namespace isg::slam
