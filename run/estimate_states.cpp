#include "run/estimate_states.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace isg::run {

const char* toString(PoseState state) {
  switch (state) {
    case PoseState::kLocalized:
      return "localized";
    case PoseState::kTracking:
      return "tracking";
    case PoseState::kLost:
      return "lost";
  }
  return "lost";
}

std::optional<PoseState> poseStateFromString(std::string_view text) {
  for (PoseState state : {PoseState::kLocalized, PoseState::kTracking, PoseState::kLost}) {
    if (text == toString(state)) return state;
  }
  return std::nullopt;
}

EstimateState EstimateStateTrack::next(PoseState state, const Eigen::Vector3d& M_t_R) {
  const double step = previous_ ? (M_t_R - *previous_).head<2>().norm() : 0.0;
  previous_ = M_t_R;
  if (state == PoseState::kLocalized) {
    sigma_ = model_.confirmed_m;
  } else {
    // The first pose of a run may be unconfirmed: it starts from the confirmed sigma too.
    sigma_ =
        std::max(sigma_, model_.confirmed_m) +
        step * (state == PoseState::kTracking ? model_.tracking_per_metre : model_.lost_per_metre);
  }
  return {state, sigma_};
}

common::Trajectory posesIn(const common::Trajectory& estimate,
                           std::span<const EstimateState> states,
                           std::initializer_list<PoseState> wanted) {
  common::Trajectory poses;
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    // A pose without a state (a record made before states were kept) was placed and confirmed.
    const PoseState state = i < states.size() ? states[i].state : PoseState::kLocalized;
    if (std::find(wanted.begin(), wanted.end(), state) != wanted.end()) {
      poses.push_back(estimate[i]);
    }
  }
  return poses;
}

std::string estimateStatesText(const common::Trajectory& estimate,
                               std::span<const EstimateState> states) {
  if (estimate.size() != states.size()) {
    throw std::logic_error("estimate_states.txt: a state for each pose of estimate.tum");
  }
  std::string text = "# stamp state sigma_xy_m (docs/formats.md, \"estimate_states.txt\")\n";
  text.reserve(text.size() + 32 * states.size());
  char row[96];
  for (std::size_t i = 0; i < states.size(); ++i) {
    // The stamp printed as estimate.tum prints it (common::toTumText), never cut.
    const auto print = [&](char* to, std::size_t size) {
      return std::snprintf(to, size, "%.9f %s %.4f\n", estimate[i].t, toString(states[i].state),
                           states[i].sigma_xy);
    };
    const int n = print(row, sizeof row);
    if (n < 0) throw std::runtime_error("estimate_states.txt: a row could not be printed");
    if (std::size_t(n) < sizeof row) {
      text.append(row, std::size_t(n));
    } else {
      std::string long_row(std::size_t(n) + 1, '\0');
      print(long_row.data(), long_row.size());
      text.append(long_row.data(), std::size_t(n));
    }
  }
  return text;
}

}  // namespace isg::run
