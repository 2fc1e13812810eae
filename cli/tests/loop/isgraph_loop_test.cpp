// The acceptance of global localization: on every reference world, the iS-Graph in the loop gets
// localized in the plan and its APE in B — 2D, no alignment, from the first localized pose on, as
// the paper measures it — stays within 5 cm on the plans and 10 cm as built; the match is never
// contradicted later (a wrong first match would be). The numbers are the ones metrics.json gets.
#include <gtest/gtest.h>

#include "cli/tests/loop/isgraph_run.hpp"
#include "run/evaluate_run.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

class ISGraphInTheLoop : public ::testing::TestWithParam<const char*> {};

TEST_P(ISGraphInTheLoop, LocalizedInThePlanWithinTheBound) {
  const std::string world = GetParam();
  const bool as_built = world.find(".asbuilt") != std::string::npos;
  const bim::Scenario scenario = worlds::loadScenarioOrBuiltin("builtin:" + world, nullptr);
  const run::RunRecord record = testing::runIsGraphInTheLoop(scenario);

  ASSERT_TRUE(record.localized_at.has_value()) << world;
  EXPECT_EQ(record.search_status, "matched");
  for (const auto& change : record.status_changes) {
    EXPECT_NE(change.status, slam::MatchStatus::kContradicted) << change.reason;
  }
  const run::RunMetrics metrics = run::evaluateRun(record).metrics;
  ASSERT_TRUE(metrics.ape_B.has_value());
  EXPECT_LE(metrics.ape_B->rmse, as_built ? 0.10 : 0.05) << world;
  // Localized well before the end: at least half the run is in B.
  EXPECT_LT(*metrics.time_to_localize, 0.5 * metrics.sim_seconds) << world;
  // Never wrong, never lost on the reference worlds.
  EXPECT_FALSE(metrics.wrongly_localized.value_or(true)) << world;
  EXPECT_TRUE(metrics.lost_at.empty()) << world;
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
