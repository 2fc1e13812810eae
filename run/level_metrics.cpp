#include "run/level_metrics.hpp"

#include <algorithm>
#include <map>

#include "bim/floor_at.hpp"

namespace isg::run {

std::vector<LevelMetrics> levelMetrics(const bim::AGraph& graph, common::PoseSequence ground_truth,
                                       const Trajectory& estimate,
                                       const std::vector<std::pair<double, double>>& ape_rows) {
  std::vector<LevelMetrics> out;
  if (graph.floors.size() < 2 || ground_truth.empty()) return out;
  const double t0 = ground_truth.time(0);
  std::map<int, int> row_of_floor;  // floor → index into out
  std::vector<int> floor_of_row;    // the ground truth's floor at each row
  auto entry = [&](int floor, double t) -> LevelMetrics& {
    auto it = row_of_floor.find(floor);
    if (it == row_of_floor.end()) {
      it = row_of_floor.emplace(floor, int(out.size())).first;
      LevelMetrics level;
      level.level = graph.floors[floor].id;
      level.arrived_at = t - t0;
      out.push_back(level);
    }
    return out[it->second];
  };
  for (std::size_t i = 0; i < ground_truth.size(); ++i) {
    const int floor = bim::floorAt(graph, ground_truth.position(i).z());
    floor_of_row.push_back(floor);
    LevelMetrics& level = entry(floor, ground_truth.time(i));
    if (i + 1 < ground_truth.size())
      level.seconds += ground_truth.time(i + 1) - ground_truth.time(i);
  }
  std::map<int, std::vector<double>> errors;
  for (const auto& [t, error] : ape_rows) {
    // The ground-truth row at or just before t.
    const std::size_t after = ground_truth.upperBound(t);
    const std::size_t i = after == 0 ? 0 : after - 1;
    const int floor = floor_of_row[i];
    LevelMetrics& level = entry(floor, ground_truth.time(i));
    // The first pose there is the first that puts the robot on that level: right after a kidnap
    // to another floor the estimate still stands where the robot was.
    const auto at = std::lower_bound(estimate.begin(), estimate.end(), t - 1e-9,
                                     [](const StampedPose& p, double s) { return p.t < s; });
    const bool on_level =
        at == estimate.end() || bim::floorAt(graph, at->pose.translation().z()) == floor;
    if (!level.first_estimate_at && on_level) level.first_estimate_at = t - t0;
    errors[floor].push_back(error);
  }
  for (auto& [floor, values] : errors) out[row_of_floor[floor]].ape_B = eval::statistics(values);
  return out;
}

}  // namespace isg::run
