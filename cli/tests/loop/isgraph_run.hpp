#pragma once

// One run of the iS-Graph in the loop on a scenario, as `isg run` makes it: the simulator's
// streams fed to the localizer with the plan's A-Graph (behind the LiDAR-inertial odometry when the
// carrier has no odometry, a handheld's), one scan thread. Shared by the loop tests.
#include "bim/agraph.hpp"
#include "bim/scenario.hpp"
#include "run/builtin_methods.hpp"
#include "run/driver.hpp"
#include "run/odometry_source.hpp"
#include "sim/scan_pipeline.hpp"
#include "sim/simulation.hpp"

namespace isg::sim::testing {

// `duration`: seconds of the route (-1: all of it).
inline run::RunRecord runIsGraphInTheLoop(const bim::Scenario& scenario, double duration = -1.0) {
  const Simulation simulation(scenario);
  const bim::AGraph plan = bim::buildAGraph(scenario.plan);
  run::LocalizerContext context;
  context.plan = &scenario.plan;
  context.agraph = &plan;
  context.level = scenario.robot.level;
  context.R_T_L = simulation.R_T_L();
  sensors::SensorStreams streams = sensorStreams(simulation, duration);
  const auto localizer =
      run::withOdometrySource(run::builtinMethods().make("is-graphs", context), streams);
  LookaheadScans scans(simulation, int(streams.scan_stamps.size()), 1);
  return run::runLocalizer({}, *localizer, std::move(streams), scans);
}

}  // namespace isg::sim::testing
