// The S-Graph's cost per keyframe as the graph grows (issue 5): a long tour of a 120-room grid
// plan, simulated in memory and fed to the S-Graph; times per keyframe (extraction + association,
// and the optimisation) reported as median and p95 around 50, 200 and 500 keyframes. Run it on
// its own: it simulates and maps about half an hour of walking.
#include <benchmark/benchmark.h>

#include "bim/json_reader.hpp"
#include "bim/plan_parser.hpp"
#include "bim/synthetic_plan.hpp"
#include "sim/simulation.hpp"
#include "slam/sgraph.hpp"
#include "slam/timing_report.hpp"

namespace isg::sim {
namespace {

void BM_SGraphGrowth(benchmark::State& state) {
  bim::GridPlanSpec spec;
  spec.rows = 10;
  spec.cols = 12;
  const nlohmann::json document = bim::makeGridPlan(spec);
  const bim::JsonSource source{"grid.json", nullptr};
  bim::Scenario scenario;
  scenario.plan = bim::parsePlan(bim::JsonNode(document, "", source));
  scenario.robot.level = "L0";
  scenario.robot.start_room = "R1";
  scenario.seed = 1;
  for (auto _ : state) {
    Simulation sim(scenario);
    const double duration = sim.duration();
    const eval::Trajectory odometry = sim.odometry(duration);
    slam::SGraph graph(sim.R_T_L());
    const auto lidar = sim.makeLidar();
    std::size_t next = 0;
    for (int k = 0; k < sim.scanCount(duration) && graph.keyframes().size() < 520; ++k) {
      const LidarScan scan = sim.scan(k, *lidar);
      while (next < odometry.size() && odometry[next].t <= scan.stamp + sim.scanPeriod()) {
        graph.addOdometry({odometry[next].t, odometry[next].pose});
        ++next;
      }
      graph.addScan({scan.stamp, scan.points});
    }
    for (const auto& row : slam::timingAt(graph.timings(), {50, 200, 500})) {
      const std::string at = std::to_string(row.keyframes);
      state.counters["extract_med_ms@" + at] = row.extraction_median_ms;
      state.counters["extract_p95_ms@" + at] = row.extraction_p95_ms;
      state.counters["optim_med_ms@" + at] = row.optimisation_median_ms;
      state.counters["optim_p95_ms@" + at] = row.optimisation_p95_ms;
    }
    state.counters["keyframes"] = double(graph.keyframes().size());
  }
}
BENCHMARK(BM_SGraphGrowth)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
}  // namespace isg::sim
