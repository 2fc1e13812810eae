#pragma once

#include "cli/common.hpp"

namespace isg::cli {

// isg slam DATASET_DIR -o RUN_DIR: replay a dataset through the S-Graph.
class SlamCommand : public Command {
 public:
  explicit SlamCommand(CLI::App& parent);
  int run() override;

 private:
  std::string dataset_;
  std::string output_;
  bool force_ = false;
  bool quiet_ = false;
};

}  // namespace isg::cli
