// The whole loop (simulator, iS-Graph, driver) over a long run: 1000 s of walking back and forth
// across a 27-room floor (a 3 × 9 grid plan), as `isg run --threads 2` runs it. Reports the real
// time factor and the process's peak resident memory; run it on its own (docs/performance.md):
//   /usr/bin/time -v build/cli/cli_bench --benchmark_filter=LongRun
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <chrono>

#include "bim/agraph.hpp"
#include "cli/bench/grid_scenario.hpp"
#include "run/builtin_methods.hpp"
#include "run/driver.hpp"
#include "sim/scan_pipeline.hpp"
#include "sim/simulation.hpp"

namespace isg::sim {
namespace {

void BM_LongRun27Rooms(benchmark::State& state) {
  bim::Scenario scenario = gridScenario(3, 9);
  // Corner to corner and back until 1000 s: R1 → R27 → R1 → …
  scenario.robot.route.kind = bim::Route::Kind::kRooms;
  for (int i = 0; i < 14; ++i) scenario.robot.route.rooms.push_back(i % 2 == 0 ? "R27" : "R1");
  const double duration = 1000.0;
  const int threads = 2;
  for (auto _ : state) {
    const Simulation sim(scenario);
    const bim::AGraph agraph = bim::buildAGraph(scenario.plan);
    sensors::SensorStreams streams = sensorStreams(sim, duration);
    run::LocalizerContext context;
    context.plan = &scenario.plan;
    context.agraph = &agraph;
    context.level = "L0";
    context.R_T_L = sim.R_T_L();
    context.threads = threads;
    const auto localizer = run::builtinMethods().make("is-graphs", context);
    LookaheadScans scans(sim, int(streams.scan_stamps.size()), threads - 1);
    const double robot_seconds = streams.duration;
    const auto start = std::chrono::steady_clock::now();
    const run::RunRecord record = run::runLocalizer({}, *localizer, std::move(streams), scans);
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    state.counters["robot_s"] = robot_seconds;
    state.counters["real_time_factor"] = robot_seconds / wall;
    state.counters["keyframes"] = double(record.map ? record.map->keyframes.size() : 0);
    state.counters["localized"] = record.localized_at ? 1.0 : 0.0;
  }
  struct rusage usage {};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["peak_rss_mb"] = usage.ru_maxrss / 1024.0;
}
BENCHMARK(BM_LongRun27Rooms)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
}  // namespace isg::sim
