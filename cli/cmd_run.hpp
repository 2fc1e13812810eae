#pragma once

#include <cstdint>
#include <optional>

#include "cli/common.hpp"
#include "cli/run_session.hpp"
#include "run/builtin_methods.hpp"

namespace isg::cli {

// isg run [PLAN|SCENARIO] [-o RUN_DIR]: the simulation in the loop with a localizer.
class RunCommand : public Command {
 public:
  explicit RunCommand(CLI::App& parent);
  int run() override;

 private:
  const run::LocalizerRegistry methods_ = run::builtinMethods();
  std::string input_;
  std::string output_;
  std::vector<std::string> method_options_;
  std::string method_ = "is-graphs";
  std::optional<std::uint64_t> seed_;
  std::string lidar_model_;
  double duration_ = -1.0;
  int threads_ = 2;
  RunMcapArguments mcap_;
  bool force_ = false;
  std::string start_pose_;  // --start-pose: X,Y,YAW or truth; empty: global localization
  std::string submission_;  // --submission DIR: the estimate as the floor-plan benchmark takes it
  bool quiet_ = false;
  bool timing_ = false;
};

}  // namespace isg::cli
