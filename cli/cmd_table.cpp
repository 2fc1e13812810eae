#include "cli/cmd_table.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
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
      "instead, --measure time-to-localize the seconds to the first localization. "
      "With --baseline, compares each cell of the baseline table (CSV, as --format csv writes "
      "it) with the runs and exits with code 4, naming every cell that is worse by more than "
      "--tolerance (in the measure's unit), failed, was wrongly localized, or has no run.\n\n"
      "Example: for m in is-graphs dead-reckoning; do isg run builtin:d1 --method $m -o "
      "runs/d1-$m; "
      "done; isg table runs/* --format csv > baseline.csv");
  app_->add_option("runs", runs_, "run folders made by isg run or isg slam")
      ->option_text("RUN_DIR")
      ->required();
  app_->add_option("--format", format_, "md, csv or latex")
      ->check(CLI::IsMember({"md", "csv", "latex"}))
      ->capture_default_str();
  app_->add_option("--measure", measure_,
                   "ape: APE RMSE in B [m]; time-wrong: seconds more than 1 m off; "
                   "time-to-localize: seconds to the first localization")
      ->check(CLI::IsMember({"ape", "time-wrong", "time-to-localize"}))
      ->capture_default_str();
  app_->add_option("--baseline", baseline_, "baseline table (CSV) to check the runs against");
  app_->add_option(
          "--tolerance", tolerance_,
          "how much a cell may exceed its baseline (metres, or seconds for the time measures)")
      ->check(nonNegativeNumber())
      ->capture_default_str();
  app_->add_option("-o,--output", output_, "write the table to this file instead of stdout");
}

int TableCommand::run() {
  // The testbed's methods first, in their order (iS-Graphs, then the baselines), like the paper.
  std::vector<std::pair<std::string, run::RunMetrics>> runs;
  for (const auto& dir : runs_) runs.emplace_back(dir, run::readMetrics(dir));
  const std::vector<std::string> names = run::builtinMethods().names();
  auto rank = [&](const run::RunMetrics& metrics) {
    return int(std::find(names.begin(), names.end(), metrics.method) - names.begin());
  };
  std::stable_sort(runs.begin(), runs.end(),
                   [&](const auto& a, const auto& b) { return rank(a.second) < rank(b.second); });
  eval::ResultTable table;
  for (const auto& [dir, metrics] : runs) {
    std::string world = metrics.world;
    if (world.rfind("builtin:", 0) == 0) world = world.substr(8);
    std::optional<double> value;
    if (measure_ == "ape") {
      if (metrics.localized && metrics.ape_B) value = metrics.ape_B->rmse;
    } else if (measure_ == "time-wrong") {
      if (metrics.localized) value = metrics.time_wrongly_localized;
    } else if (metrics.localized) {
      value = metrics.time_to_localize;
    }
    if (table.find(world, metrics.method) != nullptr) {
      throw bim::InputError(dir, "", "a second run of " + world + " with " + metrics.method);
    }
    const bool wrong = measure_ == "ape" && metrics.wrongly_localized.value_or(false);
    table.set(world, metrics.method, value, wrong);
  }
  const eval::TableFormat format = format_ == "csv"     ? eval::TableFormat::kCsv
                                   : format_ == "latex" ? eval::TableFormat::kLatex
                                                        : eval::TableFormat::kMarkdown;
  const char* caption =
      measure_ == "time-wrong"
          ? "Seconds localized more than 1 m off the ground truth (2D); - never localized"
      : measure_ == "time-to-localize"
          ? "Seconds to the first localization; - never localized"
          : "APE RMSE in B [m] (2D, no alignment, from the first localized pose on); - never "
            "localized, ✗ wrongly localized (more than 1 m off for more than 5 s)";
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
