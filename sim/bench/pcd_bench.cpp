// Writing a scan's PCD bytes, as `isg simulate` does for every turn: a D6 as-built turn encoded
// `binary` and `binary_compressed`. Reports the encoder's throughput in MB/s of uncompressed
// points (22 bytes each) and the file's size against the binary one (docs/performance.md).
#include <benchmark/benchmark.h>

#include "formats/dataset_format.hpp"
#include "sim/simulation.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

void BM_PcdEncode_D6(benchmark::State& state, formats::dataset::PcdData data) {
  static const std::vector<sensors::ScanPoint> points = [] {
    Simulation sim(worlds::loadScenarioOrBuiltin("builtin:d6.asbuilt", nullptr));
    return sim.scan(1000).points;
  }();
  std::size_t bytes = 0;
  for (auto _ : state) {
    bytes = formats::dataset::pcdBytes(points, data).size();
    benchmark::DoNotOptimize(bytes);
  }
  const double raw = 22.0 * double(points.size());
  state.SetBytesProcessed(std::int64_t(raw * double(state.iterations())));
  state.counters["points"] = double(points.size());
  state.counters["size_vs_binary"] =
      double(bytes) /
      double(formats::dataset::pcdBytes(points, formats::dataset::PcdData::kBinary).size());
}
BENCHMARK_CAPTURE(BM_PcdEncode_D6, binary, formats::dataset::PcdData::kBinary)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_PcdEncode_D6, binary_compressed, formats::dataset::PcdData::kBinaryCompressed)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace isg::sim
