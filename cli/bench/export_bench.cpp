// A dataset exported as `isg export` does it: D1 as built simulated once, then exported as a ROS 1
// bag (MB/s of bag written), the file system's cost included (docs/performance.md, "Datasets").
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>

#include "recordings/rosbag_export.hpp"
#include "sim/dataset_writer.hpp"
#include "sim/simulation.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::cli {
namespace {

namespace fs = std::filesystem;

fs::path scratch() {
  return fs::temp_directory_path() / ("isg_export_bench_" + std::to_string(::getpid()));
}

void BM_ExportRosbag_D1(benchmark::State& state) {
  const fs::path dir = scratch();
  fs::create_directories(dir);
  {
    sim::Simulation sim(worlds::loadScenarioOrBuiltin("builtin:d1.asbuilt", nullptr));
    sim::writeDataset(sim, (dir / "ds").string(), sim::DatasetOptions{}, nullptr);
  }
  recordings::RosbagExportOptions options;
  options.overwrite = true;
  recordings::ExportSummary summary;
  for (auto _ : state) {
    summary = recordings::exportRosbag((dir / "ds").string(), (dir / "d1.bag").string(), options,
                                       nullptr);
  }
  state.SetBytesProcessed(std::int64_t(summary.bytes) * std::int64_t(state.iterations()));
  state.counters["bag_MB"] = double(summary.bytes) / 1e6;
  fs::remove_all(dir);
}
BENCHMARK(BM_ExportRosbag_D1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace
}  // namespace isg::cli
