#pragma once

#include "cli/common.hpp"

namespace isg::cli {

// isg render PLAN|SCENARIO -o DIR [--time T]: pictures of the world and the walking robot.
class RenderCommand : public Command {
 public:
  explicit RenderCommand(CLI::App& parent);
  int run() override;

 private:
  std::string input_;
  std::string output_;
  double time_ = -1.0;
  int width_ = 1280;
  int height_ = 720;
};

}  // namespace isg::cli
