// World generation for large plans. The target: a 200-room plan "well under a second".
// MuJoCo's own compile of the same MJCF is measured beside it as the reference.
#include <benchmark/benchmark.h>

#include "bim/plan_parser.hpp"
#include "bim/synthetic_plan.hpp"
#include "common/json_reader.hpp"
#include "sim/mujoco_world.hpp"
#include "worlds/mjcf_generator.hpp"

namespace isg::worlds {
namespace {

nlohmann::json gridDocument(int rooms) {
  bim::GridPlanSpec spec;
  spec.rows = 10;
  spec.cols = rooms / spec.rows;
  return bim::makeGridPlan(spec);
}

// Plan JSON → validated plan → MJCF text: what `isg world` does before MuJoCo sees it.
void BM_GenerateWorldFromJson(benchmark::State& state) {
  const nlohmann::json document = gridDocument(int(state.range(0)));
  const common::JsonSource source{"grid.json", nullptr};
  std::size_t bytes = 0;
  for (auto _ : state) {
    const bim::Plan plan = bim::parsePlan(common::JsonNode(document, "", source));
    const std::string mjcf = generateMjcf(plan);
    bytes = mjcf.size();
    benchmark::DoNotOptimize(mjcf.data());
  }
  state.counters["rooms"] = double(state.range(0));
  state.counters["mjcf_bytes"] = double(bytes);
}
BENCHMARK(BM_GenerateWorldFromJson)->Arg(200)->Arg(1000)->Unit(benchmark::kMillisecond);

// MuJoCo compiling the generated MJCF (mj_loadXML from memory): the reference.
void BM_MujocoCompileGeneratedWorld(benchmark::State& state) {
  const nlohmann::json document = gridDocument(int(state.range(0)));
  const common::JsonSource source{"grid.json", nullptr};
  const std::string mjcf = generateMjcf(bim::parsePlan(common::JsonNode(document, "", source)));
  int geoms = 0;
  for (auto _ : state) {
    const sim::MujocoWorld world = sim::MujocoWorld::fromXml(mjcf);
    geoms = world.model().ngeom;
  }
  state.counters["rooms"] = double(state.range(0));
  state.counters["geoms"] = double(geoms);
}
BENCHMARK(BM_MujocoCompileGeneratedWorld)->Arg(200)->Arg(1000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace isg::worlds
