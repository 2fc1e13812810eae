#pragma once

#include <string>

#include "cli/common.hpp"

namespace isg::cli {

// isg sweep SUITE.json -o SWEEP_DIR: every world × seed × method of a suite, on local processes
// or as a Slurm array; isg sweep --collect SWEEP_DIR tabulates what is there.
class SweepCommand : public Command {
 public:
  explicit SweepCommand(CLI::App& parent);
  int run() override;

 private:
  int collect(const std::string& sweep_dir) const;

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
