#pragma once

#include "cli/common.hpp"
#include "cli/run_session.hpp"
#include "run/builtin_methods.hpp"

namespace isg::cli {

// isg slam DATASET_DIR [--plan PLAN] -o RUN_DIR: replay a dataset through a localizer.
class SlamCommand : public Command {
 public:
  explicit SlamCommand(CLI::App& parent);
  int run() override;

 private:
  const run::LocalizerRegistry methods_ = run::builtinMethods();
  std::string dataset_;
  std::string plan_;
  std::vector<std::string> method_options_;
  std::string method_;
  std::string output_;
  RunMcapArguments mcap_;
  bool force_ = false;
  bool other_plan_ = false;
  std::string start_pose_;  // --start-pose: X,Y,YAW or truth; empty: global localization
  bool quiet_ = false;
  bool timing_ = false;
  int threads_ = 2;
};

}  // namespace isg::cli
