#pragma once

#include <optional>
#include <vector>

#include "cli/common.hpp"

namespace isg::cli {

// isg table RUN_DIR... [--format md|csv|latex] [--measure M] [--baseline TABLE.csv --tolerance X]
class TableCommand : public Command {
 public:
  explicit TableCommand(CLI::App& parent);
  int run() override;

 private:
  std::vector<std::string> runs_;
  std::string format_ = "md";
  std::string measure_ = "ape";
  std::string baseline_;
  double tolerance_ = 0.01;
  std::string output_;
};

}  // namespace isg::cli
