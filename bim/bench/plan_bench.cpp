// Parsing, validation and derived geometry of large plans: grids of rooms with long walls.
#include <benchmark/benchmark.h>

#include "bim/agraph.hpp"
#include "bim/bench/grid_of.hpp"
#include "bim/plan_geometry.hpp"
#include "bim/plan_parser.hpp"
#include "bim/synthetic_plan.hpp"
#include "common/json_reader.hpp"

namespace isg::bim {
namespace {

using bench::gridOf;

void BM_ParseAndValidatePlan(benchmark::State& state) {
  const nlohmann::json document = makeGridPlan(gridOf(int(state.range(0))));
  const common::JsonSource source{"grid.json", nullptr};
  for (auto _ : state) {
    Plan plan = parsePlan(common::JsonNode(document, "", source));
    benchmark::DoNotOptimize(plan);
  }
  state.counters["rooms"] = double(state.range(0));
}
BENCHMARK(BM_ParseAndValidatePlan)->Arg(50)->Arg(200)->Unit(benchmark::kMillisecond);

void BM_LevelGeometry(benchmark::State& state) {
  const common::JsonSource source{"grid.json", nullptr};
  const nlohmann::json document = makeGridPlan(gridOf(int(state.range(0))));
  const Plan plan = parsePlan(common::JsonNode(document, "", source));
  for (auto _ : state) {
    LevelGeometry g = computeLevelGeometry(plan.levels[0]);
    benchmark::DoNotOptimize(g);
  }
  state.counters["rooms"] = double(state.range(0));
}
BENCHMARK(BM_LevelGeometry)->Arg(50)->Arg(200)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace isg::bim

namespace isg::bim {
namespace {

// The A-Graph of a plan: the "benchmark the build time" on 200 rooms (and 1000).
void BM_BuildAGraph(benchmark::State& state) {
  const common::JsonSource source{"grid.json", nullptr};
  const nlohmann::json document = makeGridPlan(gridOf(int(state.range(0))));
  const Plan plan = parsePlan(common::JsonNode(document, "", source));
  for (auto _ : state) {
    AGraph graph = buildAGraph(plan);
    benchmark::DoNotOptimize(graph);
  }
  state.counters["rooms"] = double(state.range(0));
}
BENCHMARK(BM_BuildAGraph)->Arg(50)->Arg(200)->Arg(1000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace isg::bim
