#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "sweep/suite.hpp"

namespace isg::sweep {

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

// What a cell's folder holds: a finished run of this cell (metrics.json reads, and is of the
// cell's world — its content hash —, method and seed), nothing, or something else (a damaged or
// foreign folder: `why` says what).
struct CellCheck {
  enum class State { kFinished, kMissing, kDamaged };
  State state = State::kMissing;
  std::string why;
};
CellCheck checkCell(const std::string& sweep_dir, const SweepCell& cell);

// True when the cell's run folder is complete and is this cell's.
bool cellFinished(const std::string& sweep_dir, const SweepCell& cell);

// Moves a damaged cell's folder out of the way, to SWEEP_DIR/.aside/<cell dir>[.N] (kept, never
// removed: it may be all that is left of a long run), and returns that path relative to SWEEP_DIR.
std::string moveCellAside(const std::string& sweep_dir, const SweepCell& cell);

}  // namespace isg::sweep
