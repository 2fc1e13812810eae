// Dataset synthesis end to end, as `isg simulate` does it: D1 as built to a compressed dataset on
// two threads (robot seconds per wall second: the real-time factor), the file system's cost
// included (docs/performance.md, "Datasets"; the export to a bag: cli/bench/export_bench.cpp).
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>

#include "sim/dataset_writer.hpp"
#include "sim/simulation.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

namespace fs = std::filesystem;

fs::path scratch() {
  return fs::temp_directory_path() / ("isg_dataset_bench_" + std::to_string(::getpid()));
}

void BM_SimulateToCompressedDataset_D1(benchmark::State& state) {
  Simulation sim(worlds::loadScenarioOrBuiltin("builtin:d1.asbuilt", nullptr));
  const fs::path dir = scratch();
  fs::create_directories(dir);
  DatasetOptions options;
  options.threads = 2;
  options.overwrite = true;
  DatasetSummary summary;
  for (auto _ : state) summary = writeDataset(sim, (dir / "ds").string(), options, nullptr);
  state.counters["real_time_factor"] = benchmark::Counter(
      summary.sim_seconds * double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["MB"] = double(summary.scan_bytes) / 1e6;
  fs::remove_all(dir);
}
BENCHMARK(BM_SimulateToCompressedDataset_D1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace
}  // namespace isg::sim
