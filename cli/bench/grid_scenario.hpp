#pragma once

// For the loop benchmarks: a scenario on a grid plan (bim/synthetic_plan.hpp), the robot starting
// in R1 on the ground floor, seed 1, the default tour.
#include <string>

#include "bim/plan_parser.hpp"
#include "bim/scenario.hpp"
#include "bim/synthetic_plan.hpp"
#include "common/json_reader.hpp"
#include "run/driver.hpp"
#include "sim/scan_pipeline.hpp"

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

// Feeds the walk's scans to `driver` as the loop does (scans the localizer will not read are
// skipped, never made) until `done(k)` before scan k, or the walk's end.
template <typename Done>
void feedScans(const sensors::SensorStreams& streams, LookaheadScans& scans,
               run::LocalizerDriver& driver, Done done) {
  for (int k = 0; k < int(streams.scan_stamps.size()) && !done(k); ++k) {
    if (driver.wants(streams.scan_stamps[k])) {
      sensors::Scan scan = scans.scan(k);
      scan.stamp = streams.scan_stamps[k];
      driver.feed(scan);
    } else {
      scans.skip(k);
      driver.skip(streams.scan_stamps[k]);
    }
  }
}

}  // namespace isg::sim
