#pragma once

#include <string>

#include "cli/common.hpp"

namespace isg::cli {

// isg bcf RUN_DIR [--world PLAN|SCENARIO] [--no-snapshots]: deviations.bcf written again.
class BcfCommand : public Command {
 public:
  explicit BcfCommand(CLI::App& parent);
  int run() override;

 private:
  std::string run_dir_;
  std::string world_;
  bool no_snapshots_ = false;
};

}  // namespace isg::cli
