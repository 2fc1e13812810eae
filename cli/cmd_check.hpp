#pragma once

#include "cli/common.hpp"

namespace isg::cli {

// isg check PLAN|SCENARIO: validate and describe, write nothing.
class CheckCommand : public Command {
 public:
  explicit CheckCommand(CLI::App& parent);
  int run() override;

 private:
  std::string input_;
  bool verbose_ = false;
};

}  // namespace isg::cli
