#pragma once

#include <Eigen/Core>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/trajectory.hpp"

namespace isg::run {

// What stands behind a pose of estimate.tum (docs/evaluation.md, "An estimate for every scan"):
// kLocalized — placed by the localizer's B_T_M and confirmed by the plan there; kTracking — placed
// by its B_T_M, but the plan does not confirm it here (an open area, beyond the drawn outline):
// its map and odometry carry it; kLost — the localizer no longer places its map in the plan, and
// the pose is the last B_T_M it gave over its map pose: dead reckoning until it is found again.
enum class PoseState { kLocalized, kTracking, kLost };

// "localized", "tracking", "lost": the spelling of estimate_states.txt and metrics.json.
const char* toString(PoseState state);
std::optional<PoseState> poseStateFromString(std::string_view text);

// A pose's state and the standard deviation of its position in the plane (metres, per axis).
struct EstimateState {
  PoseState state = PoseState::kLocalized;
  double sigma_xy = 0.0;
};

// The stated model of a pose's position uncertainty (not a covariance of the graph): a confirmed
// pose is as good as the localizer is where the plan holds it; from the last confirmed pose on it
// grows with each metre walked in the plane, at the drift rate of what carries the pose over that
// metre — the map and odometry while tracking, odometry over a restarted map while lost.
struct PoseSigmaModel {
  double confirmed_m = 0.03;         // the APE as planned and as built on the reference worlds
  double tracking_per_metre = 0.01;  // drift of the S-Graph's map between plan confirmations
  double lost_per_metre = 0.03;      // drift of a fresh map segment on odometry
};

// Follows a run's poses in order and gives each its state and sigma.
class EstimateStateTrack {
 public:
  explicit EstimateStateTrack(PoseSigmaModel model = {}) : model_(model) {}
  // `M_t_R`: the pose's position in the map frame (the distance walked is measured there).
  EstimateState next(PoseState state, const Eigen::Vector3d& M_t_R);

 private:
  PoseSigmaModel model_;
  std::optional<Eigen::Vector3d> previous_;
  double sigma_ = 0.0;
};

// estimate_states.txt: "# stamp state sigma_xy_m" then one row per pose of estimate.tum, the same
// stamps printed the same way.
// The poses of `estimate` whose state is one of `wanted`, in order.
common::Trajectory posesIn(const common::Trajectory& estimate,
                           std::span<const EstimateState> states,
                           std::initializer_list<PoseState> wanted);

std::string estimateStatesText(const common::Trajectory& estimate,
                               std::span<const EstimateState> states);

}  // namespace isg::run
