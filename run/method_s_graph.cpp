#include "run/builtin_methods.hpp"
#include "slam/sgraph_localizer.hpp"

namespace isg::run {

void addSGraph(LocalizerRegistry& registry) {
  registry.add({"s-graph",
                "the S-Graph alone: SLAM in its own map frame M, never localized in the plan "
                "(docs/slam.md)",
                /*needs_plan=*/false, /*given_start=*/false, [](const LocalizerContext& c) {
                  return std::make_unique<slam::SGraphLocalizer>(c.R_T_L);
                }});
}

}  // namespace isg::run
