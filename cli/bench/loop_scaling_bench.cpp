// How the whole loop (simulator, iS-Graph, driver; `isg run --threads 2`) scales with the
// building: the same 300 s of the default tour on D1 (2 rooms), D6 (17 rooms on two floors), a
// 27-room and a 200-room grid plan. Reports the real time factor, milliseconds of CPU per second
// of robot time for making scans and for the localizer, the time to build the world, and the
// process's peak resident memory. Run one building per process so the peak is its own
// (docs/performance.md):
//   build/cli/cli_bench --benchmark_filter='LoopScaling/grid200'
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <string>

#include "bim/agraph.hpp"
#include "cli/bench/grid_scenario.hpp"
#include "run/builtin_methods.hpp"
#include "run/driver.hpp"
#include "sim/scan_pipeline.hpp"
#include "sim/simulation.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

constexpr double kRobotSeconds = 300.0;
constexpr int kThreads = 2;

bim::Scenario scenarioFor(const std::string& building) {
  if (building == "grid27") return gridScenario(3, 9);
  if (building == "grid200") return gridScenario(10, 20);
  return worlds::loadScenarioOrBuiltin("builtin:" + building, nullptr);
}

void BM_LoopScaling(benchmark::State& state, const std::string& building) {
  const bim::Scenario scenario = scenarioFor(building);
  using Clock = std::chrono::steady_clock;
  auto since = [](Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  };
  for (auto _ : state) {
    const auto setup_start = Clock::now();
    const Simulation sim(scenario);
    const bim::AGraph agraph = bim::buildAGraph(scenario.plan);
    const double setup_s = since(setup_start);
    sensors::SensorStreams streams = sensorStreams(sim, kRobotSeconds);
    run::LocalizerContext context;
    context.plan = &scenario.plan;
    context.agraph = &agraph;
    context.level = scenario.robot.level;
    context.R_T_L = sim.R_T_L();
    context.threads = kThreads;
    const auto localizer = run::builtinMethods().make("is-graphs", context);
    LookaheadScans scans(sim, int(streams.scan_stamps.size()), kThreads - 1);
    const double robot_seconds = streams.duration;
    const auto start = Clock::now();
    const run::RunRecord record = run::runLocalizer({}, *localizer, std::move(streams), scans);
    const double wall = since(start);
    const sensors::StageTimes& t = record.stage_times;
    const double scan_s = t.seconds("poses") + t.seconds("casting") + t.seconds("noise");
    int rooms = 0;
    for (const auto& level : scenario.plan.levels) rooms += int(level.rooms.size());
    state.counters["rooms"] = rooms;
    state.counters["robot_s"] = robot_seconds;
    state.counters["setup_s"] = setup_s;
    state.counters["real_time_factor"] = robot_seconds / wall;
    state.counters["scans_ms_per_robot_s"] = 1e3 * scan_s / robot_seconds;
    state.counters["localizer_ms_per_robot_s"] = 1e3 * record.localizer_seconds / robot_seconds;
    // Every stage, in ms per robot-second (docs/performance.md, "Stage timing of a run").
    for (const auto& [stage, seconds] : t.stages()) {
      std::string name = "ms_" + stage;
      std::replace(name.begin(), name.end(), ' ', '_');
      state.counters[name] = 1e3 * seconds / robot_seconds;
    }
    state.counters["keyframes"] = double(record.map ? record.map->keyframes.size() : 0);
    state.counters["localized"] = record.localized_at ? 1.0 : 0.0;
  }
  struct rusage usage {};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["peak_rss_mb"] = usage.ru_maxrss / 1024.0;
}
BENCHMARK_CAPTURE(BM_LoopScaling, d1, std::string("d1.asbuilt"))
    ->Iterations(1)
    ->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_LoopScaling, d6, std::string("d6.asbuilt"))
    ->Iterations(1)
    ->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_LoopScaling, grid27, std::string("grid27"))
    ->Iterations(1)
    ->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_LoopScaling, grid200, std::string("grid200"))
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace
}  // namespace isg::sim
