#pragma once

#include <ceres/ceres.h>
#include <numbers>

#include <Eigen/Geometry>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bim/agraph.hpp"
#include "bim/agraph_optimizer.hpp"
#include "bim/plane_manifold.hpp"
#include "slam/graph_matching.hpp"
#include "slam/localizer.hpp"
#include "slam/sgraph.hpp"

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
  // many keyframes; once localized, the correspondences are refreshed at every keyframe and a
  // full match runs again with every new room, to catch a contradiction.
  int retry_keyframes = 5;
};

// One change of the matching status, for the run's log.
struct MatchEvent {
  double stamp = 0.0;
  int keyframe = 0;
  MatchStatus status = MatchStatus::kNotYet;
  std::string reason;
};

// The iS-Graph (paper §IV–V): the S-Graph, matched against the plan's A-Graph, then merged with
// it. Until the match is unique it localizes in M only; from then on B_T_M is part of every
// window optimisation, with plane-to-plane and room-to-room factors and the A-Graph's own wall
// and room factors and plane priors, and its pose in B is B_T_M · M_T_R.
class ISGraphLocalizer : public Localizer {
 public:
  ISGraphLocalizer(const Eigen::Isometry3d& R_T_L, const bim::AGraph& plan,
                   const ISGraphOptions& options = {});

  std::string name() const override { return "is-graphs"; }
  void pushOdometry(const Odometry& odometry) override { graph_.addOdometry(odometry); }
  void pushScan(const Scan& scan) override;
  std::optional<Odometry> poseInMap() const override { return graph_.latestPose(); }
  std::optional<Eigen::Isometry3d> mapInPlan() const override;
  nlohmann::json graph() const override;
  std::optional<std::string> searchStatus() const override { return toString(status_); }
  std::vector<StatusChange> statusChanges() const override;
  std::optional<MapDiagnostics> mapDiagnostics() const override { return graph_.diagnostics(); }

  const SGraph& sgraph() const { return graph_; }
  MatchStatus status() const { return status_; }
  const std::vector<MatchEvent>& events() const { return events_; }
  const std::optional<MatchResult>& lastMatch() const { return last_match_; }
  // The S-Graph as the matcher sees it now.
  MatchInput matchInput() const;
  // Seconds spent in full matching attempts, one entry per attempt.
  const std::vector<double>& matchingTimes() const { return matching_times_; }

 private:
  void onKeyframe(double stamp);
  void record(double stamp, MatchStatus status, const std::string& reason);
  void adopt(const Verification& answer);
  void addPlanFactors(ceres::Problem& problem, const std::set<int>& planes,
                      const std::vector<int>& rooms);
  void addSurface(ceres::Problem& problem, int surface);

  ISGraphOptions options_;
  const bim::AGraph* plan_;
  SGraph graph_;
  GraphMatcher matcher_;
  bim::AGraphState plan_state_;
  bim::PlaneManifold plane_manifold_;
  ceres::HuberLoss huber_{1.0};

  MatchStatus status_ = MatchStatus::kNotYet;
  bool localized_ = false;
  Eigen::Vector3d B_T_M_ = Eigen::Vector3d::Zero();  // x, y, yaw: optimised
  double B_T_M_z_ = 0.0;
  std::map<int, int> plane_matches_;  // S-plane → A-surface
  std::map<int, int> room_matches_;   // S-room → A-room
  std::optional<MatchResult> last_match_;
  std::vector<MatchEvent> events_;
  std::vector<double> matching_times_;
  std::size_t rooms_at_last_attempt_ = 0;
  int keyframes_at_last_attempt_ = 0;
  std::set<int> surfaces_in_problem_;  // per optimisation
};

}  // namespace isg::slam
