#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "cli/suite.hpp"

namespace isg::cli {

// The Slurm backend of isg sweep (docs/sweeps.md): one array task per cell left to run. The task
// runs `isg sweep --cell K SWEEP_DIR`, which runs cell K as the local backend would (same run
// folder, same failure record), so --collect reads both backends' folders alike.

// Writes SWEEP_DIR/slurm-cells.txt (the cell index of each array task, one per line) and
// SWEEP_DIR/sweep.sbatch; returns the script's path. `isg` is the executable the tasks run.
std::string writeSlurmScript(const std::string& sweep_dir, const Suite& suite,
                             const std::vector<std::size_t>& pending, const std::string& isg);

// The script's text (for the tests and --dry-run's listing).
std::string slurmScript(const std::string& sweep_dir, const Suite& suite, std::size_t tasks,
                        const std::string& isg);

// Submits the script with `sbatch --parsable` (and --wait: returns when every task has ended).
// Returns the job id. A missing sbatch or a refused submission is an InputError saying what
// sbatch said.
std::string submitSlurm(const std::string& script, bool wait);

}  // namespace isg::cli
