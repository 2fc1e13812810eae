// Collecting a sweep: 1000 run folders (50 worlds × 2 methods × 10 seeds) read and tabulated by
// isg sweep --collect's code, against reading the same files' bytes and nothing else.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "run/run_metrics.hpp"
#include "sweep/collect.hpp"

namespace {

namespace fs = std::filesystem;

isg::eval::Statistics statsOf(double rmse) {
  isg::eval::Statistics s;
  s.count = 400;
  s.rmse = rmse;
  s.mean = 0.9 * rmse;
  s.median = 0.85 * rmse;
  s.std = 0.3 * rmse;
  s.min = 0.01 * rmse;
  s.max = 2.5 * rmse;
  s.sse = s.count * rmse * rmse;
  return s;
}

// A sweep folder of 1000 finished cells, made once.
struct SweepFixture {
  fs::path dir = fs::temp_directory_path() / "isg_bench_sweep_1000";
  std::vector<isg::sweep::SweepCell> cells;

  SweepFixture() {
    fs::remove_all(dir);
    for (int w = 0; w < 50; ++w) {
      for (const char* method : {"is-graphs", "amcl"}) {
        for (int seed = 1; seed <= 10; ++seed) {
          isg::sweep::SweepCell cell;
          cell.world = "office-" + std::to_string(w);
          cell.method = method;
          cell.seed = std::uint64_t(seed);
          cell.dir = cell.world + "/" + method + "/seed-" + std::to_string(seed);
          isg::run::RunMetrics m;
          m.world = "worlds/" + cell.world + ".asbuilt.json";
          m.method = method;
          m.seed = cell.seed;
          m.scans = 1200;
          m.sim_seconds = 120.0;
          m.wall_seconds = 1.1;
          m.real_time_factor = 109.0;
          m.localized = true;
          m.time_to_localize = 12.0 + seed;
          m.distance_to_localize = 4.0;
          m.rooms_visited_to_localize = 2;
          m.share_localized = 0.9;
          m.ape_B = statsOf(0.02 + 0.001 * seed);
          m.ape_B_rotation_deg = statsOf(0.4);
          m.ape_M_se3 = statsOf(0.03);
          m.ape_odometry_from_true_start = statsOf(0.4);
          m.wrongly_localized = false;
          m.time_wrongly_localized = 0.0;
          m.max_error_B = 0.1;
          fs::create_directories(dir / cell.dir);
          std::ofstream(dir / cell.dir / "metrics.json") << isg::run::metricsToJson(m).dump(2);
          cells.push_back(cell);
        }
      }
    }
  }
  ~SweepFixture() { fs::remove_all(dir); }
};

void BM_CollectSweep_1000RunFolders(benchmark::State& state) {
  const SweepFixture f;  // written before the timed loop
  for (auto _ : state) {
    const auto collected = isg::sweep::collectSweep(f.dir.string(), f.cells);
    if (collected.finished != 1000) state.SkipWithError("not every cell was read");
    benchmark::DoNotOptimize(collected.table.table.rows.size());
  }
  state.counters["folders"] = 1000;
}
BENCHMARK(BM_CollectSweep_1000RunFolders)->Unit(benchmark::kMillisecond);

// The reference: the same 1000 metrics.json read into memory, parsed by nothing.
void BM_ReadTheSame1000Files(benchmark::State& state) {
  const SweepFixture f;  // written before the timed loop
  for (auto _ : state) {
    std::size_t bytes = 0;
    for (const auto& cell : f.cells) {
      std::ifstream in(f.dir / cell.dir / "metrics.json");
      std::stringstream text;
      text << in.rdbuf();
      bytes += text.str().size();
    }
    benchmark::DoNotOptimize(bytes);
  }
}
BENCHMARK(BM_ReadTheSame1000Files)->Unit(benchmark::kMillisecond);

}  // namespace
