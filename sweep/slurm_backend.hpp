#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "sweep/suite.hpp"

namespace isg::sweep {

// The Slurm backend of isg sweep (docs/sweeps.md): one array task per cell left to run. The task
// runs `isg sweep --cell K SWEEP_DIR`, which runs cell K as the local backend would (same run
// folder, same failure record), so --collect reads both backends' folders alike.

// Writes SWEEP_DIR/slurm-cells.txt (the cell index of each array task, one per line) and
// SWEEP_DIR/sweep.sbatch; returns the script's path. `isg` is the executable the tasks run.
std::string writeSlurmScript(const std::string& sweep_dir, const Suite& suite,
                             const std::vector<std::size_t>& pending, const std::string& isg,
                             std::size_t max_array_size);

// The script's text (for the tests and --dry-run's listing). Task T of an array submitted with
// the script argument OFFSET runs the cell on line OFFSET+T+1 of slurm-cells.txt.
std::string slurmScript(const std::string& sweep_dir, const Suite& suite, std::size_t tasks,
                        const std::string& isg, std::size_t max_array_size);

// Slurm's default MaxArraySize: an array's task indices are below it.
inline constexpr std::size_t kSlurmDefaultMaxArraySize = 1001;

// The cluster's MaxArraySize as `scontrol show config` gives it; Slurm's default when scontrol is
// missing or does not say (a --dry-run away from the cluster).
std::size_t slurmMaxArraySize();

// One array of the submission: the tasks [offset, offset + count) of slurm-cells.txt.
struct SlurmArray {
  std::size_t offset = 0, count = 0;
};

// The tasks split into arrays of at most `max_array_size` (a sweep larger than the site's
// MaxArraySize is submitted as several arrays of the same script).
std::vector<SlurmArray> slurmArrays(std::size_t tasks, std::size_t max_array_size);

// "sbatch [OPTIONS] --array=0-N SCRIPT OFFSET": the command that submits one array.
std::string sbatchCommand(const std::string& script, const SlurmArray& array,
                          const std::string& options = "");

// Submits every array with `sbatch --parsable` (with --wait, all at once, returning when every
// task of every array has ended). Returns the job ids. A missing sbatch or a refused submission
// is an InputError saying what sbatch said.
std::vector<std::string> submitSlurm(const std::string& script,
                                     const std::vector<SlurmArray>& arrays, bool wait);

}  // namespace isg::sweep
