// A localizer that says it will not read a scan (Localizer::wantsScan) must mean it: the loop
// then never makes that scan, and the run must be the very run in which every scan was made and
// fed. Checked bit for bit on the estimate files, for each method that skips.
#include <gtest/gtest.h>

#include "bim/agraph.hpp"
#include "common/tum.hpp"
#include "run/builtin_methods.hpp"
#include "run/driver.hpp"
#include "sim/scan_pipeline.hpp"
#include "sim/simulation.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

struct Estimates {
  std::string map, plan;
  int read = 0;
};

Estimates runOnce(const std::string& method, bool feed_every_scan) {
  const bim::Scenario scenario = worlds::loadScenarioOrBuiltin("builtin:d2.asbuilt", nullptr);
  const Simulation sim(scenario);
  const bim::AGraph agraph = bim::buildAGraph(scenario.plan);
  const sensors::SensorStreams streams = sensorStreams(sim, 25.0);
  run::LocalizerContext context;
  context.plan = &scenario.plan;
  context.agraph = &agraph;
  context.level = scenario.robot.level;
  context.R_T_L = sim.R_T_L();
  context.seed = scenario.seed;
  const auto localizer = run::builtinMethods().make(method, context);
  run::LocalizerDriver driver(*localizer, streams.odometry, streams.scan_period);
  LookaheadScans scans(sim, int(streams.scan_stamps.size()), 1);
  Estimates out;
  for (int k = 0; k < int(streams.scan_stamps.size()); ++k) {
    const double stamp = streams.scan_stamps[k];
    if (driver.wants(stamp) || feed_every_scan) {
      sensors::Scan scan = scans.scan(k);
      scan.stamp = stamp;
      driver.feed(scan);
      ++out.read;
    } else {
      scans.skip(k);
      driver.skip(stamp);
    }
  }
  out.map = common::toTumText(driver.estimateMap());
  out.plan = common::toTumText(driver.estimate());
  return out;
}

TEST(ScanSkipping, SkippingTheScansALocalizerWillNotReadChangesNothing) {
  for (const std::string method : {"is-graphs", "s-graph", "amcl"}) {
    const Estimates skipping = runOnce(method, false);
    const Estimates feeding = runOnce(method, true);
    EXPECT_EQ(feeding.read, 250) << method;  // 25 s at 10 Hz
    EXPECT_LT(skipping.read, feeding.read / 2) << method;
    EXPECT_GT(skipping.map.size(), 1000u) << method;
    EXPECT_EQ(skipping.map, feeding.map) << method;
    EXPECT_EQ(skipping.plan, feeding.plan) << method;
  }
}

}  // namespace
}  // namespace isg::sim
