#include "cli/cmd_table.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "common/output_path.hpp"
#include "eval/table.hpp"
#include "run/builtin_methods.hpp"
#include "run/run_metrics.hpp"
#include "sweep/run_table.hpp"
#include "sweep/suite.hpp"

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
      "the plan rooms the robot had stood in by then, --measure deviation-recall the share of "
      "the walls built shifted or turned that deviations.json found (among those seen over half "
      "their length) and --measure deviation-offset-error the mean error of their measured "
      "offsets; the other graded measures likewise: deviation-precision, deviation-angle-error "
      "[°], deviation-pivot-error [m], progress-recall and progress-precision (walls built in "
      "part), built-length-error [m] (and built-length-error-seen: over the walls seen end to "
      "end), missing-recall, missing-precision, extra-recall, "
      "extra-precision, column-recall, column-precision and column-offset-error [m] (columns "
      "moved or not built) (docs/deviations.md; simulated runs, whose scenario knows the "
      "truth), "
      "--measure floor-plan-score the Hilti × Trimble 2026 floor-plan localization score (0 … "
      "100, docs/evaluation.md), --measure map-to-plan-median the median distance of the map's "
      "points to the plan's wall faces and --measure map-to-plan-off-length the metres of faces "
      "along which the map lies 4 cm off or more (any method whose map was placed in the plan, "
      "with or without ground truth; docs/deviations.md). "
      "With --baseline, compares each cell of the baseline table (CSV, as --format csv writes "
      "it) with the runs and exits with code 4, naming every cell that is worse by more than "
      "--tolerance (in the measure's unit; for the recalls, precisions and floor-plan-score, "
      "lower by more), failed, was "
      "wrongly localized, or has no run.\n\n"
      "Runs of one world and method with different seeds make one cell: mean ± sample standard "
      "deviation over the seeds that localized correctly, k/n seeds localized correctly, w✗ "
      "seeds wrongly localized. In CSV the method's column holds the mean (a number only when "
      "every seed localized, ✗ when any was wrong: that is what --baseline compares) and four "
      "columns \"METHOD: std\", \": localized\", \": runs\", \": wrong\" follow it. A last row "
      "counts the worlds each method localized correctly on every seed.\n\n"
      "Runs in a plan of several levels add a row per level under their world's (\"WORLD / "
      "LEVEL\", docs/evaluation.md): with --measure ape the APE in B taken while on that level, "
      "with --measure time-to-localize the seconds from first arriving there to the first pose in "
      "B there (0 when it arrived localized), with the map-to-plan measures the map's points on "
      "that level.\n\n"
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
                   "metres walked by then; rooms-to-localize: plan rooms stood in by then; "
                   "deviation-recall: share of the walls built shifted or turned that the "
                   "deviation report found; deviation-offset-error: their offsets' mean error "
                   "[m]; the other graded deviation measures (see below); floor-plan-score: the "
                   "floor-plan localization score, 0 … 100; map-to-plan-median [m] and "
                   "map-to-plan-off-length [m]: the map against the plan's walls")
      ->check(CLI::IsMember(sweep::kRunTableMeasures))
      ->capture_default_str();
  app_->add_option("--baseline", baseline_, "baseline table (CSV) to check the runs against");
  app_->add_option("--tolerance", tolerance_,
                   "how much a cell may exceed its baseline, in the measure's unit")
      ->check(nonNegativeNumber())
      ->capture_default_str();
  app_->add_option("-o,--output", output_, "write the table to this file instead of stdout");
}

int TableCommand::run() {
  const run::LocalizerRegistry methods = run::builtinMethods();
  const common::OutputKind outputKind = format_ == "csv"     ? common::OutputKind::kTableCsv
                                        : format_ == "latex" ? common::OutputKind::kTableLatex
                                                             : common::OutputKind::kTableMarkdown;
  if (!output_.empty()) {
    // Replaced only if isg wrote it: never a run folder, the baseline or a file of the user's.
    std::vector<std::string> inputs = runs_;
    inputs.push_back(baseline_);
    common::checkOutputPath(output_, {outputKind, inputs, true, false});
  }
  // The testbed's methods first, in their order (iS-Graphs, then the baselines), like the paper.
  std::vector<std::pair<std::string, run::RunMetrics>> runs;
  std::vector<sweep::AbsentRun> failed;
  for (const auto& dir : runs_) {
    // A sweep's failure record (what SWEEP_DIR/*/*/seed-* also matches): a seed that failed,
    // counted in its cell as such.
    if (const std::string suffix = ".failed.json";
        dir.size() > suffix.size() &&
        dir.compare(dir.size() - suffix.size(), suffix.size(), suffix) == 0 &&
        std::filesystem::is_regular_file(dir)) {
      const nlohmann::json record = common::readJsonFile(dir);
      const common::JsonSource source{dir, nullptr};
      const common::JsonNode root(record, "", source);
      failed.push_back({root.field("world").text(), methods.canonical(root.field("method").text()),
                        root.field("seed").unsignedInteger(), true});
      continue;
    }
    // A sweep folder given for its run folders: say which command reads it.
    if (std::filesystem::is_regular_file(std::filesystem::path(dir) / sweep::kSweepPlanFile)) {
      throw common::InputError(dir, "",
                               "a sweep folder, not a run folder: isg sweep --collect " + dir +
                                   " tabulates it (or give its run folders, " + dir +
                                   "/*/*/seed-*)");
    }
    runs.emplace_back(dir, run::readMetrics(dir));
  }
  const auto [table, caption] = sweep::tabulateRuns(std::move(runs), measure_, methods, failed);
  const eval::TableFormat format = format_ == "csv"     ? eval::TableFormat::kCsv
                                   : format_ == "latex" ? eval::TableFormat::kLatex
                                                        : eval::TableFormat::kMarkdown;
  const std::string text = eval::formatTable(table, format, caption);
  if (output_.empty()) {
    std::printf("%s", text.c_str());
  } else {
    writeFileAtomically(output_, common::outputMark(outputKind, text));
  }
  if (baseline_.empty()) return kExitOk;
  common::checkRegularFile(baseline_);
  std::ifstream in(baseline_);
  if (!in) throw common::InputError(baseline_, "", "cannot read (no such file?)");
  std::stringstream content;
  content << in.rdbuf();
  eval::ResultTable baseline;
  try {
    baseline = eval::parseTableCsv(content.str());
  } catch (const std::invalid_argument& e) {
    throw common::InputError(baseline_, "", e.what());
  }
  for (auto& column : baseline.columns) column = methods.canonical(column);  // renamed methods
  const auto regressions =
      eval::findRegressions(baseline, table, tolerance_, sweep::higherIsBetter(measure_));
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
