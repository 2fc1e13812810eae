#pragma once

#include "cli/common.hpp"

namespace isg::cli {

// isg eval GT.tum EST.tum [--align none|se3|sim3] [--project xy] [--json]: APE (and RPE) as evo.
class EvalCommand : public Command {
 public:
  explicit EvalCommand(CLI::App& parent);
  int run() override;

 private:
  std::string reference_;
  std::string estimate_;
  std::string align_ = "none";
  std::string project_;
  double max_diff_ = 0.01;
  int rpe_delta_ = 0;
  bool json_ = false;
};

}  // namespace isg::cli
