// Long corridors (docs/matching.md, "Holding the map along a corridor"): on a generated floor of
// 195 offices along corridors up to 100 m long, walked for 20 minutes with the legged base's
// drifting odometry, the map must be held along the corridors where the window's walls all face
// one way. First the recent walls' own vote did it (without it the estimate slid half a metre
// along the corridor for minutes: APE in B 0.234 m here, with it 0.171 m); now the door jambs and
// the whole-map bends do, and that vote is off while the map bends (`isg run` with two threads:
// 0.295 m with neither, 0.025 m now).
#include <gtest/gtest.h>

#include "bim/plan_parser.hpp"
#include "cli/tests/loop/isgraph_run.hpp"
#include "common/json_reader.hpp"
#include "run/evaluate_run.hpp"
#include "worlds/plan_generator.hpp"

namespace isg::sim {
namespace {

TEST(LongCorridors, TheRecentWallsHoldTheMapAlongThem) {
  worlds::GeneratorSpec spec;
  spec.rooms = 200;
  spec.seed = 1;
  const worlds::GeneratedBuilding building = worlds::generateBuilding(spec);
  // The plan itself, toured from the generated scenario's start.
  nlohmann::json scenario_json = building.scenario;
  scenario_json.erase("as_built");
  const common::JsonSource plan_source{building.name + ".json", nullptr};
  const bim::Plan plan = bim::parsePlan(common::JsonNode(building.plan, "", plan_source));
  const common::JsonSource scenario_source{building.name + ".json", nullptr};
  const bim::Scenario scenario = bim::parseScenario(
      common::JsonNode(scenario_json, "", scenario_source), [&](const common::JsonNode&) {
        return bim::LoadedPlan{plan, plan_source.file};
      });
  const run::RunMetrics metrics =
      run::evaluateRun(testing::runIsGraphInTheLoop(scenario, 1200.0)).metrics;
  ASSERT_TRUE(metrics.localized);
  ASSERT_TRUE(metrics.wrongly_localized.has_value() && metrics.ape_B.has_value());
  EXPECT_FALSE(*metrics.wrongly_localized);
  EXPECT_LT(metrics.ape_B->rmse, 0.2);
}

}  // namespace
}  // namespace isg::sim
