#include "common/angles.hpp"
#include "run/builtin_methods.hpp"
#include "slam/isgraph/isgraph_localizer.hpp"

namespace isg::run {

void addISGraphs(LocalizerRegistry& registry) {
  registry.add(
      {.name = "is-graphs",
       .summary = "the S-Graph matched to and merged with the plan's A-Graph: global "
                  "localization in the plan (docs/matching.md)",
       .needs_plan = true,
       .takes_start_pose = true,
       .make = [](const LocalizerContext& c) {
         slam::ISGraphOptions options;
         options.sgraph.threads = c.threads;
         auto localizer = std::make_unique<slam::ISGraphLocalizer>(c.R_T_L, *c.agraph, options);
         localizer->setImuMount(c.R_T_I);
         if (c.given_start_B_T_M) {
           const Eigen::Isometry3d& B_T_M = *c.given_start_B_T_M;
           localizer->giveStart(Eigen::Vector3d(B_T_M.translation().x(), B_T_M.translation().y(),
                                                common::yawOf(B_T_M.linear())));
         }
         if (c.given_start_at) {
           const Eigen::Isometry3d& B_T_R = c.given_start_at->B_T_R;
           localizer->giveStartAt(c.given_start_at->stamp,
                                  Eigen::Vector3d(B_T_R.translation().x(), B_T_R.translation().y(),
                                                  common::yawOf(B_T_R.linear())));
         }
         return localizer;
       }});
}

}  // namespace isg::run
