#pragma once

#include "cli/common.hpp"

namespace isg::cli {

// isg inspect [PLAN|SCENARIO]: generate the world, load it in MuJoCo, step it, report.
class InspectCommand : public Command {
 public:
  explicit InspectCommand(CLI::App& parent);
  int run() override;

 private:
  std::string input_;
  int steps_ = 500;
};

}  // namespace isg::cli
