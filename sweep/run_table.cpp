#include "sweep/run_table.hpp"

#include <algorithm>
#include <map>
#include <set>

#include "common/input_error.hpp"

namespace isg::sweep {

namespace {

// The runs of one cell: one per seed.
struct CellRuns {
  std::vector<std::uint64_t> seeds;
  std::vector<std::optional<double>> values;
  std::vector<bool> wrong_runs;
  bool wrong = false;
  int failed = 0, not_run = 0;
};

// A world's row: its name, and the start of its hash when runs of that name are of different
// worlds (runs without a hash, from before hashes were recorded, count as one more world).
std::map<std::string, std::string> rowNames(
    const std::vector<std::pair<std::string, run::RunMetrics>>& runs) {
  std::map<std::string, std::set<std::string>> hashes;
  for (const auto& [dir, metrics] : runs) {
    hashes[shortWorld(metrics.world)].insert(metrics.world_hash.value_or(""));
  }
  std::map<std::string, std::string> rows;  // key: name + "\n" + hash
  for (const auto& [dir, metrics] : runs) {
    const std::string name = shortWorld(metrics.world);
    const std::string hash = metrics.world_hash.value_or("");
    std::string row = name;
    if (hashes[name].size() > 1) {
      row += hash.empty() ? " [no world hash]" : " [" + hash.substr(7, 8) + "]";
    }
    rows[name + "\n" + hash] = row;
  }
  return rows;
}

}  // namespace

std::string shortWorld(const std::string& world) {
  return world.rfind("builtin:", 0) == 0 ? world.substr(8) : world;
}

RunTable tabulateRuns(std::vector<std::pair<std::string, run::RunMetrics>> runs,
                      const std::string& measure, const run::LocalizerRegistry& methods,
                      const std::vector<AbsentRun>& absent) {
  for (auto& run : runs) run.second.method = methods.canonical(run.second.method);  // old names
  const std::vector<std::string> names = methods.names();
  auto rank = [&](const run::RunMetrics& metrics) {
    return int(std::find(names.begin(), names.end(), metrics.method) - names.begin());
  };
  std::stable_sort(runs.begin(), runs.end(),
                   [&](const auto& a, const auto& b) { return rank(a.second) < rank(b.second); });
  // A deviation measure is missing from a run localized correctly on a building built as planned:
  // its table counts the runs with a number.
  const bool graded = measure == "deviation-recall" || measure == "deviation-offset-error";
  // Cells in first-seen order; several seeds of a world and method make one cell.
  std::vector<std::pair<std::string, std::string>> order;
  std::map<std::pair<std::string, std::string>, CellRuns> cells;
  std::vector<std::string> uncounted;
  const std::map<std::string, std::string> row_names = rowNames(runs);
  bool split_rows = false;
  for (const auto& entry : runs) {
    // Named references, not a structured binding: the lambda below captures them (clang 14).
    const std::string& dir = entry.first;
    const run::RunMetrics& metrics = entry.second;
    const std::string world =
        row_names.at(shortWorld(metrics.world) + "\n" + metrics.world_hash.value_or(""));
    split_rows = split_rows || world != shortWorld(metrics.world);
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
    } else if (graded) {
      // Graded deviation reports only (a simulated building with its truth).
      if (metrics.deviations && metrics.deviations->grade) {
        const run::DeviationGrade& grade = *metrics.deviations->grade;
        value = measure == "deviation-recall" ? grade.recall : grade.offset_error_m;
      }
    } else if (metrics.localized) {
      value = metrics.time_to_localize;
    }
    const bool wrong = measure == "ape" && metrics.wrongly_localized.value_or(false);
    auto add = [&](const std::string& row, std::optional<double> number) {
      const auto key = std::make_pair(row, column);
      if (!cells.count(key)) order.push_back(key);
      CellRuns& cell = cells[key];
      if (std::find(cell.seeds.begin(), cell.seeds.end(), metrics.seed) != cell.seeds.end()) {
        throw common::InputError(dir, "",
                                 "a second run of " + world + " with " + metrics.method +
                                     " and seed " + std::to_string(metrics.seed));
      }
      cell.seeds.push_back(metrics.seed);
      cell.values.push_back(number);
      cell.wrong_runs.push_back(wrong);
      cell.wrong = cell.wrong || wrong;
    };
    add(world, value);
    // Several storeys: a row per level under the world's (a wrong run is wrong on each): the APE
    // taken there, or the seconds from arriving there to the first pose in B there.
    if (slam_only || (measure != "ape" && measure != "time-to-localize")) continue;
    for (const run::LevelMetrics& level : metrics.levels) {
      std::optional<double> number;
      if (measure == "ape" && metrics.localized && level.ape_B) number = level.ape_B->rmse;
      if (measure == "time-to-localize" && level.first_estimate_at) {
        number = *level.first_estimate_at - level.arrived_at;
      }
      add(world + " / " + level.level, number);
    }
  }
  // The seeds without a result count in their cell: as runs, never as localized.
  bool any_absent = false;
  for (const auto& a : absent) {
    const run::MethodInfo* info = methods.find(a.method);
    const std::string column =
        info != nullptr && info->slam_only ? a.method + " (SE(3) in M)" : a.method;
    const auto key = std::make_pair(shortWorld(a.world), column);
    if (!cells.count(key)) order.push_back(key);
    CellRuns& cell = cells[key];
    cell.seeds.push_back(a.seed);
    cell.values.push_back(std::nullopt);
    cell.wrong_runs.push_back(false);
    (a.failed ? cell.failed : cell.not_run) += 1;
    any_absent = true;
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
  // Statistics whenever a cell has several seeds, or seeds without a result: a lone "-" would
  // read as "never localized".
  const bool with_stats = most_seeds > 1 || any_absent;
  if (with_stats) {
    for (const auto& key : order) {
      const CellRuns& cell = cells.at(key);
      eval::CellStats stats = eval::cellStats(cell.values, cell.wrong_runs);
      stats.failed = cell.failed;
      stats.not_run = cell.not_run;
      table.setStats(key.first, key.second, stats);
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
      : measure == "deviation-recall"
          ? "Recall of the walls built shifted or turned, among those seen over half their "
            "length (deviations.json against the scenario's as_built); - no graded report, or no "
            "such wall to find"
      : measure == "deviation-offset-error"
          ? "Mean error [m] of the offsets measured for the walls built shifted or turned "
            "(deviations.json against the scenario's as_built); - no graded report, or no such "
            "wall found"
          : "APE RMSE in B [m] (2D, no alignment, from the first localized pose on); - never "
            "localized, ✗ wrongly localized (more than 1 m off for more than 5 s)";
  if (graded) table.count_label = eval::kGradedCountRowLabel;
  if (with_stats) {
    caption += ". Each cell aggregates its seeds (up to " + std::to_string(most_seeds) +
               (graded ? "): mean ± sample standard deviation over the seeds with a number, then "
                         "k/n seeds with one"
                       : "): mean ± sample standard deviation over the seeds localized "
                         "correctly, then k/n seeds localized correctly and w✗ seeds wrongly "
                         "localized");
    if (any_absent) {
      caption +=
          " (n counts the suite's seeds: those that failed or have not run are said, and "
          "count as not localized)";
    }
    caption +=
        "; CSV gives the mean (a number only when every seed localized, ✗ when any was wrong) "
        "and the statistics in columns of their own";
  }
  if (split_rows) {
    caption +=
        ". Rows marked [hash] are different buildings of one name, told apart by the "
        "start of their content hash";
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

}  // namespace isg::sweep
