#pragma once

#include "cli/common.hpp"

namespace isg::cli {

// isg agraph PLAN [-o agraph.json] [--svg agraph.svg]: plan → A-Graph.
class AGraphCommand : public Command {
 public:
  explicit AGraphCommand(CLI::App& parent);
  int run() override;

 private:
  std::string input_;
  std::string output_;
  std::string svg_;
  std::string level_;
};

}  // namespace isg::cli
