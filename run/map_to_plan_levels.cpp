#include "run/map_to_plan_levels.hpp"

#include <cmath>

#include "run/map_plan_error.hpp"

namespace isg::run {

std::vector<slam::LevelAgainstPlan> mapAgainstPlan(const RunRecord& run,
                                                   const std::vector<std::string>& levels,
                                                   const slam::MapAgainstPlanOptions& options) {
  if (!run.setup.agraph || !run.final_B_T_M) return {};
  return slam::measureMapAgainstPlan(
      *run.setup.agraph, levels,
      [&](const std::function<void(const Eigen::Vector3d&)>& visit) {
        forEachPlacedMapPoint(run, visit);
      },
      options);
}

RunMetrics::MapToPlan::Level levelSummary(const slam::LevelAgainstPlan& level, double off_m) {
  RunMetrics::MapToPlan::Level out;
  out.level = level.level;
  out.points = std::int64_t(level.points);
  out.near_share = level.near_share;
  out.median_m = level.median_m;
  out.p95_m = level.p95_m;
  out.stretches = int(level.stretches.size());
  const slam::FaceStretch* farthest = nullptr;
  for (const auto& s : level.stretches) {
    if (std::abs(s.mean_m) >= off_m) {
      ++out.off_stretches;
      out.off_length_m += (s.end - s.start).norm();
    }
    if (farthest == nullptr || std::abs(s.mean_m) > std::abs(farthest->mean_m)) farthest = &s;
  }
  if (farthest != nullptr) {
    out.farthest = RunMetrics::MapToPlan::Level::Farthest{farthest->surface, farthest->mean_m,
                                                          farthest->start, farthest->end};
  }
  return out;
}

}  // namespace isg::run
