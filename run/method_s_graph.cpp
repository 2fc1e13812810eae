#include "run/builtin_methods.hpp"
#include "slam/sgraph/sgraph_localizer.hpp"

namespace isg::run {

void addSGraph(LocalizerRegistry& registry) {
  registry.add({.name = "s-graph",
                .summary = "the S-Graph alone: SLAM in its own map frame M, never localized in "
                           "the plan (docs/slam.md)",
                .slam_only = true,
                .make = [](const LocalizerContext& c) {
                  slam::SGraphOptions options;
                  options.threads = c.threads;
                  auto localizer = std::make_unique<slam::SGraphLocalizer>(c.R_T_L, options);
                  localizer->setImuMount(c.R_T_I);
                  return localizer;
                }});
}

}  // namespace isg::run
