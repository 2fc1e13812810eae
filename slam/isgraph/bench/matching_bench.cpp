// One matching attempt (hypothesise, verify, cluster, refine, decide) on a 200-room plan, for
// S-Graphs of 1, 4, 8 and 20 walked rooms, against building the matcher's grid index (done once
// per plan). Short walks are ambiguous on this plan, so their attempts also seed from corners
// (docs/matching.md): the slowest case.
#include <benchmark/benchmark.h>

#include <random>

#include "bim/agraph.hpp"
#include "bim/plan_parser.hpp"
#include "bim/synthetic_plan.hpp"
#include "common/json_reader.hpp"
#include "slam/isgraph/graph_matching.hpp"
#include "slam/isgraph/tests/synthetic_sgraph.hpp"

namespace {

const isg::bim::AGraph& grid200() {
  static const isg::bim::AGraph graph = [] {
    isg::bim::GridPlanSpec spec;
    spec.rows = 10;
    spec.cols = 20;
    spec.size_seed = 17;
    const isg::common::JsonSource source{"grid.json", nullptr};
    return isg::bim::buildAGraph(
        isg::bim::parsePlan(isg::common::JsonNode(isg::bim::makeGridPlan(spec), "", source)));
  }();
  return graph;
}

void BM_MatchingAttempt_200Rooms(benchmark::State& state) {
  const auto& graph = grid200();
  const isg::slam::GraphMatcher matcher(graph);
  std::mt19937_64 rng(42);
  const auto walk = isg::testing::walkRooms(graph, 57, int(state.range(0)), rng);
  const auto cut = isg::testing::cutSGraph(graph, walk, {12.0, -7.0, 2.1}, rng);
  int hypotheses = 0;
  bool matched = false;
  for (auto _ : state) {
    const auto result = matcher.match(cut.input);
    hypotheses = result.hypotheses;
    matched = result.status == isg::slam::MatchStatus::kMatched;
    benchmark::DoNotOptimize(result.best.score);
  }
  state.counters["hypotheses"] = hypotheses;
  state.counters["matched"] = matched;
  state.counters["s_planes"] = double(cut.input.planes.size());
}
BENCHMARK(BM_MatchingAttempt_200Rooms)
    ->Arg(1)
    ->Arg(4)
    ->Arg(8)
    ->Arg(20)
    ->Unit(benchmark::kMillisecond);

void BM_MatcherIndex_200Rooms(benchmark::State& state) {
  const auto& graph = grid200();
  for (auto _ : state) {
    const isg::slam::GraphMatcher matcher(graph);
    benchmark::DoNotOptimize(&matcher);
  }
}
BENCHMARK(BM_MatcherIndex_200Rooms)->Unit(benchmark::kMillisecond);

}  // namespace
