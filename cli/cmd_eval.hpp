#pragma once

#include <optional>

#include "cli/common.hpp"
#include "eval/ape.hpp"
#include "eval/coverage.hpp"

namespace isg::cli {

// isg eval GT.tum EST.tum [--align none|se3|sim3] [--project xy] [--json] [--plot OUT.svg]: APE
// (and RPE) as evo; with --floor-plan-score [--run-start S], the floor-plan benchmark's score of
// the estimate file as given.
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
  std::string plot_;
  bool floor_plan_score_ = false;
  std::optional<double> run_start_;

  int scoreFloorPlan(const common::Trajectory& reference, const common::Trajectory& estimate) const;
  std::string rpeNotComputable(std::size_t associated) const;
  void writePlot(const common::Trajectory& reference, const common::Trajectory& estimate,
                 const eval::ErrorResult& ape, const std::string& how,
                 const eval::Coverage& coverage) const;
};

}  // namespace isg::cli
