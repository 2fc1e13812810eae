// The S-Graph's cost per keyframe as the graph grows: a long tour of a 120-room grid
// plan, simulated in memory and fed to the S-Graph; times per keyframe (the front end, plane
// extraction alone, and the optimisation) reported as median and p95 around 50, 200 and 500
// keyframes (a hundred keyframes each). Run it on its own: it simulates and maps about half an hour
// of walking.
#include <benchmark/benchmark.h>

#include <algorithm>

#include "cli/bench/grid_scenario.hpp"
#include "run/builtin_methods.hpp"
#include "run/driver.hpp"
#include "run/map_diagnosis.hpp"
#include "sim/scan_pipeline.hpp"
#include "sim/simulation.hpp"

namespace isg::sim {
namespace {

void BM_SGraphGrowth(benchmark::State& state) {
  const bim::Scenario scenario = gridScenario(10, 12);
  for (auto _ : state) {
    const Simulation sim(scenario);
    const sensors::SensorStreams streams = sensorStreams(sim, -1.0);
    run::LocalizerContext context;
    context.R_T_L = sim.R_T_L();
    const auto localizer = run::builtinMethods().make("s-graph", context);
    run::LocalizerDriver driver(*localizer, streams.odometry, streams.scan_period);
    LookaheadScans scans(sim, int(streams.scan_stamps.size()), 1);
    std::size_t keyframes = 0;
    feedScans(streams, scans, driver, [&](int k) {
      if (k % 50 == 0) keyframes = localizer->mapDiagnostics()->keyframes.size();
      return keyframes >= 560;
    });
    const auto map = *localizer->mapDiagnostics();
    // The solve and merging alone, without room detection, over the same keyframes as the rows
    // below: [n - 50, n + 50).
    for (int at : {50, 200, 500}) {
      std::vector<double> solve, residuals;
      for (int k = std::max(0, at - 50); k < std::min(int(map.timings.size()), at + 50); ++k) {
        solve.push_back(1e3 * map.timings[k].solve_s);
        residuals.push_back(map.timings[k].window_residuals);
      }
      if (solve.size() < 5) continue;
      std::sort(solve.begin(), solve.end());
      state.counters["solve_med_ms@" + std::to_string(at)] = solve[solve.size() / 2];
      state.counters["solve_p95_ms@" + std::to_string(at)] =
          solve[std::min(solve.size() - 1, std::size_t(0.95 * double(solve.size())))];
      std::sort(residuals.begin(), residuals.end());
      state.counters["residuals_med@" + std::to_string(at)] = residuals[residuals.size() / 2];
      state.counters["residuals_max@" + std::to_string(at)] = residuals.back();
    }
    for (const auto& row : run::diagnoseMap(map, {}, nullptr, "").timing) {
      const std::string at = std::to_string(row.keyframes);
      state.counters["extract_med_ms@" + at] = row.extraction_median_ms;
      state.counters["extract_p95_ms@" + at] = row.extraction_p95_ms;
      state.counters["planes_med_ms@" + at] = row.planes_median_ms;
      state.counters["planes_p95_ms@" + at] = row.planes_p95_ms;
      state.counters["optim_med_ms@" + at] = row.optimisation_median_ms;
      state.counters["optim_p95_ms@" + at] = row.optimisation_p95_ms;
    }
    state.counters["keyframes"] = double(map.keyframes.size());
  }
}
BENCHMARK(BM_SGraphGrowth)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
}  // namespace isg::sim
