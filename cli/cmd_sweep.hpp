#pragma once

#include <string>
#include <vector>

#include "cli/common.hpp"
#include "sweep/suite.hpp"

namespace isg::cli {

// isg sweep SUITE.json -o SWEEP_DIR: every world × seed × method of a suite, on local processes
// or as a Slurm array; isg sweep --collect SWEEP_DIR tabulates what is there.
class SweepCommand : public Command {
 public:
  explicit SweepCommand(CLI::App& parent);
  int run() override;

 private:
  int collect(const std::string& sweep_dir) const;
  // The cells not finished as Slurm job arrays (--dry-run: the script only; --wait: collected).
  int runOnSlurm(const sweep::Suite& suite, const std::vector<sweep::SweepCell>& cells) const;
  // Every cell on the local pool, then the table.
  int runLocally(const std::vector<sweep::SweepCell>& cells) const;

  std::string input_;
  std::string output_;
  int jobs_ = 1;
  std::string backend_ = "local";
  bool dry_run_ = false;
  bool wait_ = false;
  bool collect_ = false;
  bool rerun_changed_ = false;
  long cell_ = -1;
  std::string measure_ = "ape";
  bool quiet_ = false;
};

}  // namespace isg::cli
