#include "cli/cmd_table.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "eval/table.hpp"
#include "run/builtin_methods.hpp"
#include "run/run_metrics.hpp"

namespace isg::cli {

TableCommand::TableCommand(CLI::App& parent) {
  app_ = parent.add_subcommand("table", "APE table of run folders, like the paper's Table I");
  app_->footer(
      "Reads RUN_DIR/metrics.json of each run folder (made by isg run or isg slam) and prints one "
      "row per world and one column per method: the APE RMSE in the plan frame B (2D, no "
      "alignment, from the first localized pose on), \"-\" where the method never localized, or "
      "\"✗\" where it was wrongly localized (a pose more than 1 m off for more than 5 s on end, "
      "docs/evaluation.md). --measure time-wrong tabulates the seconds spent more than 1 m off "
      "instead, --measure time-to-localize the seconds to the first localization, "
      "--measure distance-to-localize the metres walked by then and --measure rooms-to-localize "
      "the plan rooms the robot had stood in by then. "
      "With --baseline, compares each cell of the baseline table (CSV, as --format csv writes "
      "it) with the runs and exits with code 4, naming every cell that is worse by more than "
      "--tolerance (in the measure's unit), failed, was wrongly localized, or has no run.\n\n"
      "Runs of one world and method with different seeds make one cell: mean ± sample standard "
      "deviation over the seeds that localized correctly, k/n seeds localized correctly, w✗ "
      "seeds wrongly localized. In CSV the method's column holds the mean (a number only when "
      "every seed localized, ✗ when any was wrong: that is what --baseline compares) and four "
      "columns \"METHOD: std\", \": localized\", \": runs\", \": wrong\" follow it. A last row "
      "counts the worlds each method localized correctly on every seed.\n\n"
      "Example: for m in is-graphs amcl odometry; do for s in 1 2 3; do isg run builtin:d1 "
      "--method $m --seed $s -o runs/d1-$m-$s; done; done; isg table runs/* --format csv > "
      "baseline.csv");
  app_->add_option("runs", runs_, "run folders made by isg run or isg slam")
      ->option_text("RUN_DIR")
      ->required();
  app_->add_option("--format", format_, "md, csv or latex")
      ->check(CLI::IsMember({"md", "csv", "latex"}))
      ->capture_default_str();
  app_->add_option("--measure", measure_,
                   "ape: APE RMSE in B [m]; time-wrong: seconds more than 1 m off; "
                   "time-to-localize: seconds to the first localization; distance-to-localize: "
                   "metres walked by then; rooms-to-localize: plan rooms stood in by then")
      ->check(CLI::IsMember(
          {"ape", "time-wrong", "time-to-localize", "distance-to-localize", "rooms-to-localize"}))
      ->capture_default_str();
  app_->add_option("--baseline", baseline_, "baseline table (CSV) to check the runs against");
  app_->add_option("--tolerance", tolerance_,
                   "how much a cell may exceed its baseline, in the measure's unit")
      ->check(nonNegativeNumber())
      ->capture_default_str();
  app_->add_option("-o,--output", output_, "write the table to this file instead of stdout");
}

namespace {

// The runs of one cell: one per seed.
struct CellRuns {
  std::vector<std::uint64_t> seeds;
  std::vector<std::optional<double>> values;
  std::vector<bool> wrong_runs;
  bool wrong = false;
};

}  // namespace

int TableCommand::run() {
  const run::LocalizerRegistry methods = run::builtinMethods();
  // The testbed's methods first, in their order (iS-Graphs, then the baselines), like the paper.
  std::vector<std::pair<std::string, run::RunMetrics>> runs;
  for (const auto& dir : runs_) {
    runs.emplace_back(dir, run::readMetrics(dir));
    runs.back().second.method = methods.canonical(runs.back().second.method);  // old names
  }
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
      if (measure_ == "ape" && metrics.ape_M_se3) value = metrics.ape_M_se3->rmse;
      if (std::find(uncounted.begin(), uncounted.end(), column) == uncounted.end()) {
        uncounted.push_back(column);
      }
    } else if (measure_ == "ape") {
      if (metrics.localized && metrics.ape_B) value = metrics.ape_B->rmse;
    } else if (measure_ == "time-wrong") {
      if (metrics.localized) value = metrics.time_wrongly_localized;
    } else if (measure_ == "distance-to-localize") {
      if (metrics.localized) value = metrics.distance_to_localize;
    } else if (measure_ == "rooms-to-localize") {
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
    const bool wrong = measure_ == "ape" && metrics.wrongly_localized.value_or(false);
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
  const eval::TableFormat format = format_ == "csv"     ? eval::TableFormat::kCsv
                                   : format_ == "latex" ? eval::TableFormat::kLatex
                                                        : eval::TableFormat::kMarkdown;
  std::string caption =
      measure_ == "time-wrong"
          ? "Seconds localized more than 1 m off the ground truth (2D); - never localized"
      : measure_ == "time-to-localize" ? "Seconds to the first localization; - never localized"
      : measure_ == "distance-to-localize"
          ? "Metres walked (2D) to the first localization; - never localized"
      : measure_ == "rooms-to-localize"
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
  const std::string text = eval::formatTable(table, format, caption);
  if (output_.empty()) {
    std::printf("%s", text.c_str());
  } else {
    writeFileAtomically(output_, text);
  }
  if (baseline_.empty()) return kExitOk;
  std::ifstream in(baseline_);
  if (!in) throw bim::InputError(baseline_, "", "cannot read (no such file?)");
  std::stringstream content;
  content << in.rdbuf();
  eval::ResultTable baseline;
  try {
    baseline = eval::parseTableCsv(content.str());
  } catch (const std::invalid_argument& e) {
    throw bim::InputError(baseline_, "", e.what());
  }
  for (auto& column : baseline.columns) column = methods.canonical(column);  // renamed methods
  const auto regressions = eval::findRegressions(baseline, table, tolerance_);
  for (const auto& r : regressions) {
    std::fprintf(stderr, "isg table: regression: %s (tolerance %.3f m)\n", r.describe().c_str(),
                 tolerance_);
  }
  if (!regressions.empty()) return kExitRegression;
  std::fprintf(stderr, "isg table: no cell regressed against %s (tolerance %.3f m)\n",
               baseline_.c_str(), tolerance_);
  return kExitOk;
}

}  // namespace isg::cli
