#pragma once

#include "cli/common.hpp"

namespace isg::cli {

// isg world PLAN|SCENARIO [-o world.xml]: plan (+ as-built deviations) → MuJoCo MJCF.
class WorldCommand : public Command {
 public:
  explicit WorldCommand(CLI::App& parent);
  int run() override;

 private:
  std::string input_;
  std::string output_;
  bool no_ceilings_ = false;
};

}  // namespace isg::cli
