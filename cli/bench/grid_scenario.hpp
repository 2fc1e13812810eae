#pragma once

// For the loop benchmarks: a scenario on a grid plan (bim/synthetic_plan.hpp), the robot starting
// in R1 on the ground floor, seed 1, the default tour.
#include <string>

#include "bim/plan_parser.hpp"
#include "bim/scenario.hpp"
#include "bim/synthetic_plan.hpp"
#include "common/json_reader.hpp"

namespace isg::sim {

inline bim::Scenario gridScenario(int rows, int cols) {
  bim::GridPlanSpec spec;
  spec.rows = rows;
  spec.cols = cols;
  const nlohmann::json document = bim::makeGridPlan(spec);
  const common::JsonSource source{
      "grid-" + std::to_string(rows) + "x" + std::to_string(cols) + ".json", nullptr};
  bim::Scenario scenario;
  scenario.plan = bim::parsePlan(common::JsonNode(document, "", source));
  scenario.robot.level = "L0";
  scenario.robot.start_room = "R1";
  scenario.seed = 1;
  return scenario;
}

}  // namespace isg::sim
