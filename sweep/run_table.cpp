#include "sweep/run_table.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>

#include "common/input_error.hpp"
#include "common/json_reader.hpp"

namespace isg::sweep {

namespace {

// Of counts found, missed or falsely reported: found over the two; none without either.
std::optional<double> share(int found, int other) {
  if (found + other == 0) return std::nullopt;
  return double(found) / double(found + other);
}

// A graded deviation measure: its number in a grade and what the table's caption says it is.
struct GradedMeasure {
  const char* name;
  std::optional<double> (*of)(const run::DeviationGrade&);
  const char* caption;
};

const GradedMeasure kGradedMeasures[] = {
    {"deviation-recall", [](const run::DeviationGrade& g) { return g.recall; },
     "Recall of the walls built shifted or turned, among those seen over half their length"},
    {"deviation-precision", [](const run::DeviationGrade& g) { return g.precision; },
     "Precision of the walls reported shifted or turned, among those seen over half their "
     "length"},
    {"deviation-offset-error", [](const run::DeviationGrade& g) { return g.offset_error_m; },
     "Mean error [m] of the offsets measured for the walls built shifted or turned"},
    {"deviation-angle-error", [](const run::DeviationGrade& g) { return g.angle_error_deg; },
     "Mean error [°] of the angles measured for the walls built shifted or turned"},
    {"deviation-pivot-error", [](const run::DeviationGrade& g) { return g.pivot_error_m; },
     "Mean error [m] of the point along the wall each wall turned as built was found turned "
     "about"},
    {"progress-recall", [](const run::DeviationGrade& g) { return g.partly_recall; },
     "Recall of the walls built in part, reported partly built or not built"},
    {"progress-precision", [](const run::DeviationGrade& g) { return g.partly_precision; },
     "Precision of the walls reported partly built or not built, among the walls built in part "
     "and whole"},
    {"built-length-error", [](const run::DeviationGrade& g) { return g.built_length_error_m; },
     "Mean error [m] of the built length of the walls built in part found partly built"},
    {"built-length-error-seen",
     [](const run::DeviationGrade& g) { return g.built_length_error_seen_m; },
     "The same mean over those seen end to end (less than 0.1 m of them not seen)"},
    {"missing-recall",
     [](const run::DeviationGrade& g) { return share(g.missing_found, g.missing_missed); },
     "Recall of the walls not built, reported missing"},
    {"missing-precision",
     [](const run::DeviationGrade& g) { return share(g.missing_found, g.missing_false_reports); },
     "Precision of the walls reported missing"},
    {"extra-recall", [](const run::DeviationGrade& g) { return g.extra_recall; },
     "Recall of the walls built that the plan lacks, reported extra"},
    {"extra-precision", [](const run::DeviationGrade& g) { return g.extra_precision; },
     "Precision of the walls reported extra (those on a clutter box not counted)"},
    {"column-recall", [](const run::DeviationGrade& g) { return g.column_recall; },
     "Recall of the columns built moved or not built, reported moved or missing"},
    {"column-precision", [](const run::DeviationGrade& g) { return g.column_precision; },
     "Precision of the columns reported moved or missing"},
    {"column-offset-error", [](const run::DeviationGrade& g) { return g.column_offset_error_m; },
     "Mean distance [m] between the measured and the true offset of the moved columns found"},
};

const GradedMeasure& gradedMeasure(const std::string& name) {
  for (const auto& m : kGradedMeasures) {
    if (name == m.name) return m;
  }
  throw std::logic_error("not a graded measure: " + name);
}

using Runs = std::vector<std::pair<std::string, run::RunMetrics>>;

// The runs of one cell: one per seed.
struct CellRuns {
  std::vector<std::uint64_t> seeds;
  std::vector<std::optional<double>> values;
  std::vector<bool> wrong_runs;
  bool wrong = false;
  int failed = 0, not_run = 0;
};

// The cells of a table in first-seen order, keyed by (row, column).
struct Cells {
  std::vector<std::pair<std::string, std::string>> order;
  std::map<std::pair<std::string, std::string>, CellRuns> runs;

  CellRuns& at(const std::string& row, const std::string& column) {
    const auto key = std::make_pair(row, column);
    if (!runs.count(key)) order.push_back(key);
    return runs[key];
  }
};

// A world's row: its name, and the start of its hash when runs of that name are of different
// worlds (runs without a hash, from before hashes were recorded, count as one more world).
std::map<std::string, std::string> rowNames(const Runs& runs) {
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

// "particles=3000, update_min_d=0.5": the options of `options` among `keys`.
std::string optionText(const std::map<std::string, double>& options,
                       const std::set<std::string>& keys) {
  std::string text;
  for (const auto& key : keys) {
    const auto it = options.find(key);
    text += (text.empty() ? "" : ", ") + key + "=" +
            (it == options.end() ? std::string("?") : common::formatNumber(it->second));
  }
  return text;
}

// Each run's column: its method ("(SE(3) in M)" for SLAM only), and, when runs of one method ran
// with different options (metrics.json's method_options), the options that differ among them
// ("amcl [particles=3000]"). Runs that recorded no options (before they were recorded) join any.
std::vector<std::string> columnNames(const Runs& runs, const run::LocalizerRegistry& methods) {
  std::map<std::string, std::set<std::map<std::string, double>>> option_sets;
  for (const auto& [dir, metrics] : runs) {
    if (metrics.method_options) option_sets[metrics.method].insert(*metrics.method_options);
  }
  std::vector<std::string> columns;
  for (const auto& [dir, metrics] : runs) {
    const run::MethodInfo* info = methods.find(metrics.method);
    std::string column = metrics.method;
    if (info != nullptr && info->slam_only) column += " (SE(3) in M)";
    const auto& sets = option_sets[metrics.method];
    if (sets.size() > 1 && metrics.method_options) {
      std::set<std::string> differing;
      for (const auto& set : sets) {
        for (const auto& [key, value] : set) {
          for (const auto& other : sets) {
            const auto it = other.find(key);
            if (it == other.end() || it->second != value) differing.insert(key);
          }
        }
      }
      column += " [" + optionText(*metrics.method_options, differing) + "]";
    }
    columns.push_back(column);
  }
  return columns;
}

// The run's number for the measure; nullopt where it has none (never localized, no grade).
std::optional<double> measureOf(const run::RunMetrics& metrics, const std::string& measure,
                                bool slam_only) {
  if (slam_only) {
    if (measure == "ape" && metrics.ape_M_se3) return metrics.ape_M_se3->rmse;
    return std::nullopt;
  }
  if (measure == "ape") {
    if (metrics.localized && metrics.ape_B) return metrics.ape_B->rmse;
  } else if (measure == "time-wrong") {
    if (metrics.localized) return metrics.time_wrongly_localized;
  } else if (measure == "distance-to-localize") {
    if (metrics.localized) return metrics.distance_to_localize;
  } else if (measure == "rooms-to-localize") {
    if (metrics.localized && metrics.rooms_visited_to_localize) {
      return double(*metrics.rooms_visited_to_localize);
    }
  } else if (measure == "floor-plan-score") {
    // Scored with ground truth, localized or not (a run never localized scores 0).
    if (metrics.floor_plan_score) return metrics.floor_plan_score->score;
  } else if (measure == "map-to-plan-median") {
    // With or without ground truth, wherever the map was placed in the plan.
    if (metrics.map_to_plan) return metrics.map_to_plan->distance.median;
  } else if (measure == "map-to-plan-off-length") {
    if (metrics.map_to_plan) {
      double length = 0.0;
      for (const auto& level : metrics.map_to_plan->levels) length += level.off_length_m;
      return length;
    }
  } else if (isGraded(measure)) {
    // Graded deviation reports only (a simulated building with its truth).
    if (metrics.deviations && metrics.deviations->grade) {
      return gradedMeasure(measure).of(*metrics.deviations->grade);
    }
  } else if (metrics.localized) {
    return metrics.time_to_localize;
  }
  return std::nullopt;
}

// Adds one run to its cell; a second run of the cell's seed is bad input naming its folder.
void addRun(Cells& cells, const std::string& row, const std::string& column, const std::string& dir,
            const run::RunMetrics& metrics, std::optional<double> value, bool wrong) {
  CellRuns& cell = cells.at(row, column);
  if (std::find(cell.seeds.begin(), cell.seeds.end(), metrics.seed) != cell.seeds.end()) {
    throw common::InputError(dir, "",
                             "a second run of " + row + " with " + metrics.method + " and seed " +
                                 std::to_string(metrics.seed));
  }
  cell.seeds.push_back(metrics.seed);
  cell.values.push_back(value);
  cell.wrong_runs.push_back(wrong);
  cell.wrong = cell.wrong || wrong;
}

// What the caption says beyond what the cells are: how they aggregate seeds, and which rows and
// columns are split or special.
struct CaptionFacts {
  bool graded = false, with_stats = false, any_absent = false, split_rows = false;
  bool split_columns = false;
  std::size_t most_seeds = 0;
};

std::string measureCaption(const std::string& measure) {
  if (measure == "time-wrong")
    return "Seconds localized more than 1 m off the ground truth (2D); - never localized";
  if (measure == "time-to-localize") return "Seconds to the first localization; - never localized";
  if (measure == "distance-to-localize")
    return "Metres walked (2D) to the first localization; - never localized";
  if (measure == "rooms-to-localize")
    return "Plan rooms stood in by the first localization; - never localized";
  if (measure == "floor-plan-score") {
    return "Floor-plan localization score (Hilti × Trimble 2026: the mean over the poses from 5 s "
           "on of 100·e^(−0.4605·e), e the 2D error in B in metres; 0 when under 99 % of them "
           "are estimated); - no ground truth";
  }
  if (measure == "map-to-plan-median") {
    return "Median distance [m] of the map's points near the plan (within its cutoff, 0.3 m) to "
           "the plan's wall faces, the map placed by the run's final B_T_M (docs/evaluation.md, "
           "\"Map against the plan\"); - map never placed in the plan";
  }
  if (measure == "map-to-plan-off-length") {
    return "Metres of the plan's faces along which the map lies 4 cm off or more (stretches of "
           "at most 1 m with 30 points or more, docs/deviations.md, \"Where the map disagrees "
           "with the plan\"); - map never placed in the plan";
  }
  if (isGraded(measure)) {
    return std::string(gradedMeasure(measure).caption) +
           " (deviations.json against the scenario's as_built, docs/deviations.md); - no graded "
           "report, or nothing to divide by";
  }
  return "APE RMSE in B [m] (2D, no alignment, from the first localized pose on); - never "
         "localized, ✗ wrongly localized (more than 1 m off for more than 5 s)";
}

std::string caption(const std::string& measure, const CaptionFacts& facts,
                    const eval::ResultTable& table, const run::LocalizerRegistry& methods) {
  std::string text = measureCaption(measure);
  if (facts.with_stats) {
    text += ". Each cell aggregates its seeds (up to " + std::to_string(facts.most_seeds) +
            (facts.graded ? "): mean ± sample standard deviation over the seeds with a number, "
                            "then k/n seeds with one"
                          : "): mean ± sample standard deviation over the seeds localized "
                            "correctly, then k/n seeds localized correctly and w✗ seeds wrongly "
                            "localized");
    if (facts.any_absent) {
      text +=
          " (n counts the suite's seeds: those that failed or have not run are said, and "
          "count as not localized)";
    }
    text +=
        "; CSV gives the mean (a number only when every seed localized, ✗ when any was wrong) "
        "and the statistics in columns of their own";
  }
  if (facts.split_rows) {
    text +=
        ". Rows marked [hash] are different buildings of one name, told apart by the "
        "start of their content hash";
  }
  if (facts.split_columns) {
    text +=
        ". Columns marked [KEY=VALUE] are one method run with different options "
        "(--method-option), told apart by those that differ";
  }
  std::string given;
  for (const auto& column : table.columns) {
    const run::MethodInfo* info = methods.find(column);
    if (info != nullptr && info->given_start) given += (given.empty() ? "" : ", ") + column;
  }
  if (!given.empty()) {
    text += ". Given their start pose (trackers, not global localization): " + given +
            " (docs/baselines.md)";
  }
  if (!table.uncounted.empty()) text += ". SLAM only: APE of the map frame M after SE(3) alignment";
  return text;
}

// The seeds without a result count in their cell: as runs, never as localized.
bool addAbsent(Cells& cells, const std::vector<AbsentRun>& absent,
               const run::LocalizerRegistry& methods) {
  for (const auto& a : absent) {
    const run::MethodInfo* info = methods.find(a.method);
    const std::string column =
        info != nullptr && info->slam_only ? a.method + " (SE(3) in M)" : a.method;
    CellRuns& cell = cells.at(shortWorld(a.world), column);
    cell.seeds.push_back(a.seed);
    cell.values.push_back(std::nullopt);
    cell.wrong_runs.push_back(false);
    (a.failed ? cell.failed : cell.not_run) += 1;
  }
  return !absent.empty();
}

// The table of the cells: a mean only when every seed gave a number (a world a method fails on
// one seed in three is not a world it localizes in), and statistics when asked.
eval::ResultTable tableOf(const Cells& cells, bool with_stats) {
  eval::ResultTable table;
  for (const auto& key : cells.order) {
    const CellRuns& cell = cells.runs.at(key);
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
  if (!with_stats) return table;
  for (const auto& key : cells.order) {
    const CellRuns& cell = cells.runs.at(key);
    eval::CellStats stats = eval::cellStats(cell.values, cell.wrong_runs);
    stats.failed = cell.failed;
    stats.not_run = cell.not_run;
    table.setStats(key.first, key.second, stats);
  }
  return table;
}

}  // namespace

std::string shortWorld(const std::string& world) {
  return world.rfind("builtin:", 0) == 0 ? world.substr(8) : world;
}

RunTable tabulateRuns(Runs runs, const std::string& measure, const run::LocalizerRegistry& methods,
                      const std::vector<AbsentRun>& absent) {
  for (auto& run : runs) run.second.method = methods.canonical(run.second.method);  // old names
  const std::vector<std::string> names = methods.names();
  auto rank = [&](const run::RunMetrics& metrics) {
    return int(std::find(names.begin(), names.end(), metrics.method) - names.begin());
  };
  std::stable_sort(runs.begin(), runs.end(),
                   [&](const auto& a, const auto& b) { return rank(a.second) < rank(b.second); });
  CaptionFacts facts;
  // A deviation measure is missing from a run localized correctly on a building built as planned:
  // its table counts the runs with a number.
  // Likewise the map against the plan, missing where the map was never placed in the plan.
  facts.graded = isGraded(measure) || measure.starts_with("map-to-plan-");
  // Cells in first-seen order; several seeds of a world and method make one cell.
  Cells cells;
  std::vector<std::string> uncounted;
  const std::map<std::string, std::string> row_names = rowNames(runs);
  const std::vector<std::string> columns = columnNames(runs, methods);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const auto& [dir, metrics] = runs[i];
    const std::string world =
        row_names.at(shortWorld(metrics.world) + "\n" + metrics.world_hash.value_or(""));
    facts.split_rows = facts.split_rows || world != shortWorld(metrics.world);
    const std::string& column = columns[i];
    facts.split_columns = facts.split_columns || column.back() == ']';
    const run::MethodInfo* info = methods.find(metrics.method);
    const bool slam_only = info != nullptr && info->slam_only;
    if (slam_only && std::find(uncounted.begin(), uncounted.end(), column) == uncounted.end()) {
      uncounted.push_back(column);
    }
    const bool wrong = measure == "ape" && metrics.wrongly_localized.value_or(false);
    addRun(cells, world, column, dir, metrics, measureOf(metrics, measure, slam_only), wrong);
    // Several storeys: a row per level under the world's (a wrong run is wrong on each): the APE
    // taken there, or the seconds from arriving there to the first pose in B there.
    if (metrics.map_to_plan && metrics.map_to_plan->levels.size() > 1 &&
        measure.starts_with("map-to-plan-")) {
      // The map against the plan per level it has points on, whatever the method.
      for (const auto& level : metrics.map_to_plan->levels) {
        const double number = measure == "map-to-plan-median" ? level.median_m : level.off_length_m;
        addRun(cells, world + " / " + level.level, column, dir, metrics, number, false);
      }
      continue;
    }
    if (slam_only || (measure != "ape" && measure != "time-to-localize")) continue;
    for (const run::LevelMetrics& level : metrics.levels) {
      std::optional<double> number;
      if (measure == "ape" && metrics.localized && level.ape_B) number = level.ape_B->rmse;
      if (measure == "time-to-localize" && level.first_estimate_at) {
        number = *level.first_estimate_at - level.arrived_at;
      }
      addRun(cells, world + " / " + level.level, column, dir, metrics, number, wrong);
    }
  }
  facts.any_absent = addAbsent(cells, absent, methods);
  for (const auto& [key, cell] : cells.runs)
    facts.most_seeds = std::max(facts.most_seeds, cell.values.size());
  // Statistics whenever a cell has several seeds, or seeds without a result: a lone "-" would
  // read as "never localized".
  facts.with_stats = facts.most_seeds > 1 || facts.any_absent;
  eval::ResultTable table = tableOf(cells, facts.with_stats);
  table.uncounted = uncounted;
  if (facts.graded) table.count_label = eval::kGradedCountRowLabel;
  return {table, caption(measure, facts, table, methods)};
}

bool isGraded(const std::string& measure) {
  return std::any_of(std::begin(kGradedMeasures), std::end(kGradedMeasures),
                     [&](const GradedMeasure& m) { return measure == m.name; });
}

}  // namespace isg::sweep
