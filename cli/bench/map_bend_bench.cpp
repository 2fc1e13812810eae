// The cost of the merged graph's bends (ISGraphOptions::bend_keyframes, docs/matching.md) against
// the map's size: a long legged tour of a 120-room grid plan, simulated in memory and fed to the
// iS-Graph; each whole-map optimisation with the plan is timed as the run makes it, and reported
// beside the window's own solve per keyframe around 100, 200, 400 and 550 keyframes. Run it on its
// own: it simulates and maps about twenty minutes of walking.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bim/agraph.hpp"
#include "cli/bench/grid_scenario.hpp"
#include "run/driver.hpp"
#include "sim/scan_pipeline.hpp"
#include "sim/simulation.hpp"
#include "slam/isgraph/isgraph_localizer.hpp"

namespace isg::sim {
namespace {

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

void BM_MapBendAgainstKeyframes(benchmark::State& state) {
  const bim::Scenario scenario = gridScenario(10, 12);
  const bim::AGraph plan = bim::buildAGraph(scenario.plan);
  for (auto _ : state) {
    const Simulation sim(scenario);
    const sensors::SensorStreams streams = sensorStreams(sim, -1.0);
    slam::ISGraphLocalizer localizer(sim.R_T_L(), plan);
    run::LocalizerDriver driver(localizer, streams.odometry, streams.scan_period);
    LookaheadScans scans(sim, int(streams.scan_stamps.size()), 1);
    feedScans(streams, scans, driver,
              [&](int) { return localizer.sgraph().keyframes().size() >= 600; });
    const auto& timings = localizer.sgraph().timings();
    for (int at : {100, 200, 400, 550}) {
      // The bends nearest `at` keyframes (within ±50), and the window's solves there.
      std::vector<double> bend_ms, rooms, solve_ms;
      for (const auto& bend : localizer.bends()) {
        if (std::abs(bend.keyframes - at) > 50) continue;
        bend_ms.push_back(1e3 * bend.seconds);
        rooms.push_back(bend.rooms);
      }
      for (int k = std::max(0, at - 50); k < std::min(int(timings.size()), at + 50); ++k) {
        solve_ms.push_back(1e3 * timings[k].solve_s);
      }
      if (bend_ms.empty()) continue;
      const std::string suffix = "@" + std::to_string(at);
      state.counters["bend_med_ms" + suffix] = median(bend_ms);
      state.counters["rooms" + suffix] = median(rooms);
      state.counters["window_solve_med_ms" + suffix] = median(solve_ms);
    }
    double total = 0.0;
    for (const auto& bend : localizer.bends()) total += bend.seconds;
    state.counters["bends"] = double(localizer.bends().size());
    state.counters["bends_total_s"] = total;
    state.counters["keyframes"] = double(localizer.sgraph().keyframes().size());
  }
}
BENCHMARK(BM_MapBendAgainstKeyframes)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
}  // namespace isg::sim
