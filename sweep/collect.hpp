#pragma once

#include <string>
#include <vector>

#include "sweep/run_table.hpp"
#include "sweep/suite.hpp"

namespace isg::sweep {

// What a sweep folder holds: the table of its finished cells (as isg table makes it) and which
// cells failed (with the first line of their error) or have not run yet.
struct SweepCollection {
  RunTable table;
  int finished = 0;
  std::vector<std::string> failed;   // "<cell dir>: <error>"
  std::vector<std::string> missing;  // cell dirs with neither a run folder nor a failure record
};

// Reads every cell's metrics.json (a run folder) or failure record. `measure` as isg table's.
SweepCollection collectSweep(const std::string& sweep_dir, const std::vector<SweepCell>& cells,
                             const std::string& measure = "ape");

}  // namespace isg::sweep
