#include "run/map_plan_error.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>

#include "common/pose_interpolation.hpp"
#include "run/keyframe_placements.hpp"
#include "slam/deviations/plan_segment_grid.hpp"

namespace isg::run {

namespace {

// The run's robot in B at any time, as its final map places it: from the keyframe at or before it
// (the first for earlier times), carried by odometry, in B where that keyframe's segment lies
// (run/keyframe_placements.hpp); without keyframes or without an odometry stream (the method made
// its own from the scans), the online estimate in M, placed by the final B_T_M.
class FinalTrajectory {
 public:
  explicit FinalTrajectory(const RunRecord& run)
      : run_(run), placements_(keyframePlacements(run)) {}

  std::optional<Eigen::Isometry3d> B_T_R(double t) const {
    if (!run_.map || run_.map->keyframes.empty() || run_.streams.odometry.empty()) {
      const auto M_T_R = common::interpolatePose(run_.estimate_map, t);
      if (!M_T_R) return std::nullopt;
      return *run_.final_B_T_M * *M_T_R;
    }
    const auto& keyframes = run_.map->keyframes;
    auto after =
        std::upper_bound(keyframes.begin(), keyframes.end(), t,
                         [](double time, const slam::MapKeyframe& k) { return time < k.stamp; });
    if (after != keyframes.begin()) --after;
    const auto placement =
        placementOfKeyframe(run_, placements_, std::size_t(after - keyframes.begin()));
    const auto odometry = common::interpolatePose(run_.streams.odometry, t);
    if (!placement || !odometry) return std::nullopt;
    const Eigen::Isometry3d M_T_R = after->estimate * after->odometry.inverse() * *odometry;
    return *placement * M_T_R;
  }

 private:
  const RunRecord& run_;
  const std::vector<std::optional<Eigen::Isometry3d>> placements_;
};

}  // namespace

void forEachPlacedMapPoint(const RunRecord& run,
                           const std::function<void(const Eigen::Vector3d&)>& visit) {
  if (!run.final_B_T_M) return;
  const FinalTrajectory trajectory(run);
  const Eigen::Isometry3d& R_T_L = run.streams.R_T_L;
  // Poses every 10 ms across a turn: a point moves under 1 cm between them at walking speed.
  constexpr double kStep = 0.01;
  for (const auto& scan : run.map_samples) {
    if (scan.points.empty()) continue;
    float first = scan.points.front()[3], last = first;
    for (const auto& p : scan.points) first = std::min(first, p[3]), last = std::max(last, p[3]);
    std::vector<std::optional<Eigen::Isometry3d>> B_T_L;
    for (int i = 0; i <= int(std::ceil((last - first) / kStep)); ++i) {
      const auto B_T_R = trajectory.B_T_R(scan.stamp + first + i * kStep);
      B_T_L.push_back(B_T_R ? std::optional(*B_T_R * R_T_L) : std::nullopt);
    }
    for (const auto& p : scan.points) {
      const auto& pose = B_T_L[std::size_t(std::lround((p[3] - first) / kStep))];
      if (pose) visit(*pose * Eigen::Vector3d(p[0], p[1], p[2]));
    }
  }
}

void forEachWallBandMapPoint(const RunRecord& run, const MapPlanErrorOptions& options,
                             const std::function<void(const Eigen::Vector3d&)>& visit) {
  if (!run.setup.agraph) return;
  const slam::PlanSegmentGrid grid(*run.setup.agraph, options.cutoff, options.margin);
  forEachPlacedMapPoint(run, [&](const Eigen::Vector3d& p) {
    if (grid.inBand(p.z())) visit(p);
  });
}

std::optional<MapPlanError> mapPlanError(const RunRecord& run, const MapPlanErrorOptions& options) {
  if (!run.setup.agraph) return std::nullopt;
  const slam::PlanSegmentGrid grid(*run.setup.agraph, options.cutoff, options.margin);
  MapPlanError out;
  // Two passes, the first counting: the distances are the evaluation's largest array (1.8 M at
  // two hours), and a vector grown by doubling would hold up to three times their size while it
  // moves.
  std::size_t near = 0;
  forEachPlacedMapPoint(run, [&](const Eigen::Vector3d& in_B) {
    if (!grid.inBand(in_B.z())) return;
    const auto nearest = grid.nearest(in_B);
    if (nearest && nearest->distance <= options.cutoff) ++near;
  });
  std::vector<double> distances;
  distances.reserve(near);
  forEachPlacedMapPoint(run, [&](const Eigen::Vector3d& in_B) {
    if (!grid.inBand(in_B.z())) return;
    ++out.points;
    const auto nearest = grid.nearest(in_B);
    if (nearest && nearest->distance <= options.cutoff) distances.push_back(nearest->distance);
  });
  if (out.points == 0) return std::nullopt;
  out.near_share = double(distances.size()) / double(out.points);
  if (!distances.empty()) out.distance = eval::statistics(std::move(distances));
  return out;
}

}  // namespace isg::run
