#include "cli/run_table.hpp"

#include <algorithm>
#include <map>

#include "bim/input_error.hpp"

namespace isg::cli {

namespace {

// The runs of one cell: one per seed.
struct CellRuns {
  std::vector<std::uint64_t> seeds;
  std::vector<std::optional<double>> values;
  std::vector<bool> wrong_runs;
  bool wrong = false;
};

}  // namespace

RunTable tabulateRuns(std::vector<std::pair<std::string, run::RunMetrics>> runs,
                      const std::string& measure, const run::LocalizerRegistry& methods) {
  for (auto& run : runs) run.second.method = methods.canonical(run.second.method);  // old names
  const std::vector<std::string> names = methods.names();
  auto rank = [&](const run::RunMetrics& metrics) {
    return int(std::find(names.begin(), names.end(), metrics.method) - names.begin());
  };
  std::stable_sort(runs.begin(), runs.end(),
                   [&](const auto& a, const auto& b) { return rank(a.second) < rank(b.second); });
  // Cells in first-seen order; several seeds of a world and method make one cell.
  std::vector<std::pair<std::string, std::string>> order;
  std::map<std::pair<std::string, std::string>, CellRuns> cells;
  std::vector<std::string> uncounted;
  for (const auto& [dir, metrics] : runs) {
    std::string world = metrics.world;
    if (world.rfind("builtin:", 0) == 0) world = world.substr(8);
    const run::MethodInfo* info = methods.find(metrics.method);
    const bool slam_only = info != nullptr && info->slam_only;
    const std::string column = slam_only ? metrics.method + " (SE(3) in M)" : metrics.method;
    std::optional<double> value;
    if (slam_only) {
      if (measure == "ape" && metrics.ape_M_se3) value = metrics.ape_M_se3->rmse;
      if (std::find(uncounted.begin(), uncounted.end(), column) == uncounted.end()) {
        uncounted.push_back(column);
      }
    } else if (measure == "ape") {
      if (metrics.localized && metrics.ape_B) value = metrics.ape_B->rmse;
    } else if (measure == "time-wrong") {
      if (metrics.localized) value = metrics.time_wrongly_localized;
    } else if (measure == "distance-to-localize") {
      if (metrics.localized) value = metrics.distance_to_localize;
    } else if (measure == "rooms-to-localize") {
      if (metrics.localized && metrics.rooms_visited_to_localize) {
        value = double(*metrics.rooms_visited_to_localize);
      }
    } else if (metrics.localized) {
      value = metrics.time_to_localize;
    }
    const auto key = std::make_pair(world, column);
    if (!cells.count(key)) order.push_back(key);
    CellRuns& cell = cells[key];
    if (std::find(cell.seeds.begin(), cell.seeds.end(), metrics.seed) != cell.seeds.end()) {
      throw bim::InputError(dir, "",
                            "a second run of " + world + " with " + metrics.method + " and seed " +
                                std::to_string(metrics.seed));
    }
    cell.seeds.push_back(metrics.seed);
    cell.values.push_back(value);
    const bool wrong = measure == "ape" && metrics.wrongly_localized.value_or(false);
    cell.wrong_runs.push_back(wrong);
    cell.wrong = cell.wrong || wrong;
  }
  eval::ResultTable table;
  table.uncounted = uncounted;
  std::size_t most_seeds = 0;
  for (const auto& key : order) {
    const CellRuns& cell = cells.at(key);
    most_seeds = std::max(most_seeds, cell.values.size());
    // A number only when every seed gave one: a world a method fails on one seed in three is not
    // a world it localizes in.
    std::optional<double> mean = 0.0;
    for (const auto& v : cell.values) {
      if (!v) {
        mean.reset();
        break;
      }
      *mean += *v / double(cell.values.size());
    }
    table.set(key.first, key.second, mean, cell.wrong);
  }
  if (most_seeds > 1) {
    for (const auto& key : order) {
      const CellRuns& cell = cells.at(key);
      table.setStats(key.first, key.second, eval::cellStats(cell.values, cell.wrong_runs));
    }
  }
  std::string caption =
      measure == "time-wrong"
          ? "Seconds localized more than 1 m off the ground truth (2D); - never localized"
      : measure == "time-to-localize" ? "Seconds to the first localization; - never localized"
      : measure == "distance-to-localize"
          ? "Metres walked (2D) to the first localization; - never localized"
      : measure == "rooms-to-localize"
          ? "Plan rooms stood in by the first localization; - never localized"
          : "APE RMSE in B [m] (2D, no alignment, from the first localized pose on); - never "
            "localized, ✗ wrongly localized (more than 1 m off for more than 5 s)";
  if (most_seeds > 1) {
    caption += ". Each cell aggregates its seeds (up to " + std::to_string(most_seeds) +
               "): mean ± sample standard deviation over the seeds localized correctly, then "
               "k/n seeds localized correctly and w✗ seeds wrongly localized; CSV gives the mean "
               "(a number only when every seed localized, ✗ when any was wrong) and the "
               "statistics in columns of their own";
  }
  std::string given;
  for (const auto& column : table.columns) {
    const run::MethodInfo* info = methods.find(column);
    if (info != nullptr && info->given_start) given += (given.empty() ? "" : ", ") + column;
  }
  if (!given.empty()) {
    caption += ". Given their start pose (trackers, not global localization): " + given +
               " (docs/baselines.md)";
  }
  if (!uncounted.empty()) caption += ". SLAM only: APE of the map frame M after SE(3) alignment";
  return {table, caption};
}

}  // namespace isg::cli
