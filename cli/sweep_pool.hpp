#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "cli/suite.hpp"

namespace isg::cli {

// Runs sweep cells as child `isg run` processes, `jobs` at a time (docs/sweeps.md). A cell whose
// run folder already holds metrics.json is finished and skipped, so a sweep started again does
// only what is left; isg run writes its folder all at once, so a killed cell leaves nothing. Each
// child's output goes to SWEEP_DIR/logs/<cell>.log; a failed cell is recorded in
// SWEEP_DIR/<cell>.failed.json (exit status, command, the log's last lines) and the others go on.
// Children get SIGTERM when the sweep dies (PR_SET_PDEATHSIG) or is interrupted.
struct PoolOutcome {
  int finished = 0;  // ran now and wrote their folder
  int skipped = 0;   // finished before
  int failed = 0;
};

PoolOutcome runCells(const std::string& sweep_dir, const std::vector<SweepCell>& cells,
                     const std::vector<std::size_t>& indices, int jobs, bool quiet);

// The failure record of a cell, beside its run folder.
std::string failureRecordPath(const std::string& sweep_dir, const SweepCell& cell);

// True when the cell's run folder is complete.
bool cellFinished(const std::string& sweep_dir, const SweepCell& cell);

}  // namespace isg::cli
