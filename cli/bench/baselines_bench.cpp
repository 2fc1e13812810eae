// The baselines' cost per scan on D1 as built (docs/baselines.md): AMCL's filter update (motion,
// likelihood field, KLD resampling) with 500 and 2000 particles, and NDT-UKF's registration and
// filter step; the simulator's own cast of a scan is the reference measured in the same run. A
// method keeps up with the robot at k× real time when its scan costs 1/k of the scan period
// (100 ms): the counter x_real_time says so.
#include <benchmark/benchmark.h>

#include "bim/agraph.hpp"

#include "run/builtin_methods.hpp"
#include "sensors/sensor_streams.hpp"
#include "sim/scan_pipeline.hpp"
#include "sim/simulation.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

// Two hundred scans (20 s) of D1 as built and the odometry up to each.
struct Recording {
  bim::Scenario scenario;
  sensors::SensorStreams streams;
  std::vector<sensors::Scan> scans;
  Eigen::Isometry3d R_T_L;
};

const Recording& recording() {
  static const Recording r = [] {
    Recording out;
    out.scenario = worlds::loadScenarioOrBuiltin("builtin:d1.asbuilt", nullptr);
    const Simulation simulation(out.scenario);
    out.streams = sensorStreams(simulation, 20.0);
    out.R_T_L = simulation.R_T_L();
    LookaheadScans scans(simulation, int(out.streams.scan_stamps.size()), 1);
    for (int k = 0; k < int(out.streams.scan_stamps.size()); ++k) {
      out.scans.push_back(scans.scan(k));
      out.scans.back().stamp = out.streams.scan_stamps[k];
    }
    return out;
  }();
  return r;
}

// Feeds scans in order (the odometry up to each), round and round; times pushScan only.
void feed(benchmark::State& state, slam::Localizer& localizer) {
  const Recording& r = recording();
  std::size_t next_odometry = 0;
  std::size_t k = 0;
  for (auto _ : state) {
    if (k == r.scans.size()) {
      state.PauseTiming();
      k = 0;
      next_odometry = 0;
      state.ResumeTiming();
    }
    const sensors::Scan& scan = r.scans[k++];
    state.PauseTiming();
    while (next_odometry < r.streams.odometry.size() &&
           r.streams.odometry[next_odometry].t <= scan.stamp + r.streams.scan_period) {
      localizer.pushOdometry(
          {r.streams.odometry[next_odometry].t, r.streams.odometry[next_odometry].pose});
      ++next_odometry;
    }
    state.ResumeTiming();
    localizer.pushScan(scan);
  }
  state.counters["x_real_time"] = benchmark::Counter(
      r.streams.scan_period * double(state.iterations()), benchmark::Counter::kIsRate);
}

// The method as the registry builds it for a run on the recording, with these options.
std::unique_ptr<slam::Localizer> method(const std::string& name,
                                        std::map<std::string, std::string> options) {
  const Recording& r = recording();
  static const bim::AGraph agraph = bim::buildAGraph(r.scenario.plan);
  run::LocalizerContext context;
  context.plan = &r.scenario.plan;
  context.agraph = &agraph;
  context.level = r.scenario.robot.level;
  context.R_T_L = r.R_T_L;
  context.start_B_T_M = sensors::trueStartB_T_M(r.streams);
  context.seed = 1;
  context.options = std::move(options);
  return run::builtinMethods().make(name, context);
}

// A fixed particle count, and an update on every scan (not only after 0.25 m or 0.2 rad).
void BM_AmclScan(benchmark::State& state) {
  const std::string particles = std::to_string(state.range(0));
  const auto amcl = method("amcl", {{"particles", particles},
                                    {"min_particles", particles},
                                    {"update_min_d", "0"},
                                    {"update_min_a", "0"}});
  feed(state, *amcl);
}
BENCHMARK(BM_AmclScan)->Arg(500)->Arg(2000)->Unit(benchmark::kMillisecond);

void BM_NdtUkfScan(benchmark::State& state) {
  const auto ndt = method("ndt-ukf", {{"start_error", "0"}, {"start_yaw_error_deg", "0"}});
  feed(state, *ndt);
}
BENCHMARK(BM_NdtUkfScan)->Unit(benchmark::kMillisecond);

// The reference: the simulator casting one VLP-16 turn in the same world.
void BM_SimulatorScanReference(benchmark::State& state) {
  const Recording& r = recording();
  const Simulation simulation(r.scenario);
  const auto lidar = simulation.makeLidar();
  int k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(simulation.scan(k, *lidar));
    k = (k + 1) % int(r.scans.size());
  }
  state.counters["x_real_time"] = benchmark::Counter(
      r.streams.scan_period * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SimulatorScanReference)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace isg::sim
