#pragma once

#include <Eigen/Geometry>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bim/agraph.hpp"
#include "bim/plan.hpp"
#include "slam/localizer.hpp"

namespace isg::run {

// Everything a method may be built from. A method takes what it needs and ignores the rest.
struct LocalizerContext {
  const bim::Plan* plan = nullptr;      // the plan to localize in, when there is one
  const bim::AGraph* agraph = nullptr;  // its A-Graph
  std::string level;                    // the level the robot walks
  Eigen::Isometry3d R_T_L = Eigen::Isometry3d::Identity();  // the LiDAR on the base
  // The start hint: where M lies in B at the start (the true start pose). Only methods that are
  // given their start (dead reckoning, trackers) read it; global localizers never do.
  std::optional<Eigen::Isometry3d> start_B_T_M;
};

// A localization method as the command line offers it.
struct MethodInfo {
  std::string name;     // what --method takes
  std::string summary;  // one line for --help
  bool needs_plan = false;
  bool given_start = false;  // reads LocalizerContext::start_B_T_M
  std::function<std::unique_ptr<slam::Localizer>(const LocalizerContext&)> make;
};

// The methods a run can use, by name, in the order they were added (the order of tables'
// columns). A new method adds itself with add(); nothing else in the pipeline names methods.
class LocalizerRegistry {
 public:
  // Throws std::invalid_argument when the name is taken or the entry has no factory.
  void add(MethodInfo method);
  const MethodInfo* find(const std::string& name) const;
  std::vector<std::string> names() const;
  // "is-graphs: …\ns-graph: …" for --help.
  std::string help() const;
  // Builds the method. Throws std::invalid_argument for an unknown name, or when the method
  // needs a plan (or a start) that the context lacks: the caller checks find() first.
  std::unique_ptr<slam::Localizer> make(const std::string& name,
                                        const LocalizerContext& context) const;

 private:
  std::vector<MethodInfo> methods_;
};

}  // namespace isg::run
