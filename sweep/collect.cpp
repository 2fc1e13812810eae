#include "sweep/collect.hpp"

#include <filesystem>

#include "common/json_reader.hpp"
#include "run/builtin_methods.hpp"
#include "run/run_metrics.hpp"
#include "sweep/pool.hpp"

namespace isg::sweep {

SweepCollection collectSweep(const std::string& sweep_dir, const std::vector<SweepCell>& cells,
                             const std::string& measure) {
  namespace fs = std::filesystem;
  SweepCollection out;
  std::vector<std::pair<std::string, run::RunMetrics>> runs;
  std::vector<AbsentRun> absent;
  runs.reserve(cells.size());
  for (const auto& cell : cells) {
    const fs::path dir = fs::path(sweep_dir) / cell.dir;
    const CellCheck check = checkCell(sweep_dir, cell);
    if (check.state == CellCheck::State::kFinished) {
      run::RunMetrics metrics = run::readMetrics(dir.string());
      // The row is the suite's world name (a generated world's file is worlds/NAME.asbuilt.json).
      metrics.world = cell.world;
      runs.emplace_back(dir.string(), std::move(metrics));
      ++out.finished;
      continue;
    }
    if (check.state == CellCheck::State::kDamaged) {
      // Not this cell's result: counted as failed; the next isg sweep moves it aside and reruns it.
      out.failed.push_back(cell.dir + ": not a finished run of this cell (" + check.why +
                           "); isg sweep runs it again");
      absent.push_back({cell.world, cell.method, cell.seed, true});
      continue;
    }
    const std::string record = failureRecordPath(sweep_dir, cell);
    if (!fs::exists(record)) {
      out.missing.push_back(cell.dir);
      absent.push_back({cell.world, cell.method, cell.seed, false});
      continue;
    }
    std::string error = "no error line";
    try {
      const nlohmann::json failure = common::readJsonFile(record);
      if (failure.contains("error") && failure["error"].is_array() && !failure["error"].empty() &&
          failure["error"].back().is_string()) {
        error = failure["error"].back().get<std::string>();
      }
    } catch (const std::exception& e) {
      error = std::string("its failure record does not read: ") + e.what();
    }
    out.failed.push_back(cell.dir + ": " + error);
    absent.push_back({cell.world, cell.method, cell.seed, true});
  }
  out.table = tabulateRuns(std::move(runs), measure, run::builtinMethods(), absent);
  return out;
}

}  // namespace isg::sweep
