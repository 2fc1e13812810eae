// The A-Graph's optimisation (bim/optimizer/agraph_optimizer.hpp) on large plans: grids of rooms
// with long walls, from perturbed room centres.
#include <benchmark/benchmark.h>

#include "bim/agraph.hpp"
#include "bim/bench/grid_of.hpp"
#include "bim/optimizer/agraph_optimizer.hpp"
#include "bim/plan_parser.hpp"
#include "bim/synthetic_plan.hpp"
#include "common/json_reader.hpp"

namespace isg::bim {
namespace {

using bench::gridOf;

// One optimisation of the whole A-Graph from perturbed values, for scale.
void BM_OptimizeAGraph(benchmark::State& state) {
  const common::JsonSource source{"grid.json", nullptr};
  const nlohmann::json document = makeGridPlan(gridOf(int(state.range(0))));
  const Plan plan = parsePlan(common::JsonNode(document, "", source));
  const AGraph graph = buildAGraph(plan);
  for (auto _ : state) {
    AGraphState graph_state(graph);
    for (auto& r : graph_state.rooms) r.x() += 0.1;
    benchmark::DoNotOptimize(graph_state.optimize());
  }
  state.counters["rooms"] = double(state.range(0));
}
BENCHMARK(BM_OptimizeAGraph)->Arg(50)->Arg(200)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace isg::bim
