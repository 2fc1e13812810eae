#include "eval/floor_plan_score.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "eval/association.hpp"

namespace isg::eval {

namespace {

common::Trajectory from(common::PoseSequence poses, double t0) {
  common::Trajectory out;
  for (const common::StampedPose pose : poses) {
    if (pose.t >= t0) out.push_back(pose);
  }
  return out;
}

}  // namespace

double benchmarkRunStart(common::PoseSequence reference) {
  if (reference.empty()) return 0.0;
  const double first = reference[0].t;
  if (first >= kBenchmarkClockStart && first < kBenchmarkClockStart + kBenchmarkClockWindow)
    return kBenchmarkClockStart;
  return first;
}

FloorPlanScore floorPlanScore(common::PoseSequence reference, common::PoseSequence estimate,
                              const FloorPlanScoreOptions& options) {
  FloorPlanScore out;
  if (reference.empty()) return out;
  out.run_start = options.run_start.value_or(benchmarkRunStart(reference));
  const common::Trajectory scored_reference = from(reference, out.run_start + options.skip);
  const common::Trajectory scored_estimate = from(estimate, out.run_start + options.skip);
  out.poses = int(scored_reference.size());
  if (out.poses == 0 || scored_estimate.empty()) return out;
  const Association pairs = associate(scored_reference, scored_estimate, options.max_diff);
  out.associated = int(pairs.reference.size());
  double sum = 0.0;
  for (std::size_t k = 0; k < pairs.reference.size(); ++k) {
    const common::StampedPose& g = scored_reference[std::size_t(pairs.reference[k])];
    const common::StampedPose& e = scored_estimate[std::size_t(pairs.estimate[k])];
    const double error = (e.pose.translation() - g.pose.translation()).head<2>().norm();
    const double score = options.scale * std::exp(-options.decay * error);
    out.per_pose.push_back({g.t, error, score});
    sum += score;
  }
  out.coverage = double(out.associated) / double(out.poses);
  if (out.coverage >= options.min_coverage && out.associated > 0) {
    out.score = std::min(100.0, sum / double(out.associated));
  }
  return out;
}

common::Trajectory estimateAtStamps(common::PoseSequence reference, common::PoseSequence estimate,
                                    double max_gap) {
  common::Trajectory out;
  std::size_t next = 0;  // the first estimate row at or after the stamp (both in order)
  for (const common::StampedPose g : reference) {
    while (next < estimate.size() && estimate[next].t < g.t - 1e-3) ++next;
    if (next < estimate.size() && std::abs(estimate[next].t - g.t) <= 1e-3) {
      out.push_back({g.t, estimate[next].pose});
      continue;
    }
    if (next == 0 || next >= estimate.size()) continue;
    const common::StampedPose a = estimate[next - 1], b = estimate[next];
    if (b.t - a.t > max_gap) continue;
    const double w = (g.t - a.t) / (b.t - a.t);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = (1.0 - w) * a.pose.translation() + w * b.pose.translation();
    pose.linear() = Eigen::Quaterniond(a.pose.linear())
                        .slerp(w, Eigen::Quaterniond(b.pose.linear()))
                        .toRotationMatrix();
    out.push_back({g.t, pose});
  }
  return out;
}

FloorPlanScore runFloorPlanScore(common::PoseSequence ground_truth, common::PoseSequence estimate) {
  return floorPlanScore(ground_truth, estimateAtStamps(ground_truth, estimate));
}

}  // namespace isg::eval
