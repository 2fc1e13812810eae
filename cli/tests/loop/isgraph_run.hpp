#pragma once

// One run of the iS-Graph in the loop on a scenario, as `isg run` makes it: the simulator's
// streams fed to the localizer with the plan's A-Graph, one scan thread. Shared by the loop tests.
#include "bim/agraph.hpp"
#include "bim/scenario.hpp"
#include "run/builtin_methods.hpp"
#include "run/driver.hpp"
#include "sim/scan_pipeline.hpp"
#include "sim/simulation.hpp"

namespace isg::sim::testing {

inline run::RunRecord runIsGraphInTheLoop(const bim::Scenario& scenario) {
  const Simulation simulation(scenario);
  const bim::AGraph plan = bim::buildAGraph(scenario.plan);
  run::LocalizerContext context;
  context.plan = &scenario.plan;
  context.agraph = &plan;
  context.level = scenario.robot.level;
  context.R_T_L = simulation.R_T_L();
  const auto localizer = run::builtinMethods().make("is-graphs", context);
  sensors::SensorStreams streams = sensorStreams(simulation, -1.0);
  LookaheadScans scans(simulation, int(streams.scan_stamps.size()), 1);
  return run::runLocalizer({}, *localizer, std::move(streams), scans);
}

}  // namespace isg::sim::testing
