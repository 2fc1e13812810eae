// The acceptance of global localization (issue 6): on every reference world, the iS-Graph in the
// loop gets localized in the plan and its APE in B — 2D, no alignment, from the first localized
// pose on, as the paper measures it — stays within 5 cm on the plans and 10 cm as built; the
// match is never contradicted later (a wrong first match would be).
#include <gtest/gtest.h>

#include "bim/agraph.hpp"
#include "eval/ape.hpp"
#include "sim/simulation.hpp"
#include "sim/testbed_loop.hpp"
#include "slam/isgraph_localizer.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

class ISGraphInTheLoop : public ::testing::TestWithParam<const char*> {};

TEST_P(ISGraphInTheLoop, LocalizedInThePlanWithinTheBound) {
  const std::string world = GetParam();
  const bool as_built = world.find(".asbuilt") != std::string::npos;
  const bim::Scenario scenario = worlds::loadScenarioOrBuiltin("builtin:" + world, nullptr);
  Simulation simulation(scenario);
  const bim::AGraph plan = bim::buildAGraph(scenario.plan);
  slam::ISGraphLocalizer localizer(simulation.R_T_L(), plan);
  const LoopResult loop = runLoop(simulation, localizer);

  ASSERT_TRUE(loop.localized_at.has_value()) << world;
  EXPECT_EQ(localizer.status(), slam::MatchStatus::kMatched);
  for (const auto& event : localizer.events()) {
    EXPECT_NE(event.status, slam::MatchStatus::kContradicted) << event.reason;
  }
  eval::ErrorOptions planar;
  planar.project_xy = true;
  const auto ape = eval::absolutePoseError(loop.ground_truth, loop.estimate, planar);
  EXPECT_LE(ape.translation_stats.rmse, as_built ? 0.10 : 0.05) << world;
  // Localized well before the end: at least half the run is in B.
  EXPECT_LT(*loop.localized_at - loop.ground_truth.front().t, 0.5 * loop.sim_seconds) << world;
}

INSTANTIATE_TEST_SUITE_P(ReferenceWorlds, ISGraphInTheLoop,
                         ::testing::Values("d1", "d1.asbuilt", "d2", "d2.asbuilt", "d3",
                                           "d3.asbuilt", "d4", "d4.asbuilt", "d5", "d5.asbuilt",
                                           "d6", "d6.asbuilt"),
                         [](const auto& test_info) {
                           std::string name = test_info.param;
                           for (char& c : name) {
                             if (c == '.') c = '_';
                           }
                           return name;
                         });

}  // namespace
}  // namespace isg::sim
