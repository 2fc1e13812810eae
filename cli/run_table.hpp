#pragma once

#include <string>
#include <utility>
#include <vector>

#include "eval/table.hpp"
#include "run/localizer_registry.hpp"
#include "run/run_metrics.hpp"

namespace isg::cli {

// The table of `isg table` and `isg sweep --collect`: rows worlds, columns methods in the
// registry's order, cells aggregated over seeds (docs/evaluation.md), with a caption that says
// what the cells are. `runs` are (run folder, its metrics) pairs; `measure` is one of ape,
// time-wrong, time-to-localize, distance-to-localize, rooms-to-localize. Two runs of one world,
// method and seed are bad input naming the second folder.
struct RunTable {
  eval::ResultTable table;
  std::string caption;
};
RunTable tabulateRuns(std::vector<std::pair<std::string, run::RunMetrics>> runs,
                      const std::string& measure, const run::LocalizerRegistry& methods);

}  // namespace isg::cli
