// The fast ray caster against MuJoCo's mj_ray on the same VLP-16 scans, in the largest
// reference world (D6 as built) and in a 200-room plan. Each benchmark casts one full 10 Hz turn
// (1808 × 16 rays) from each of a few sensor positions inside rooms; items/s = rays/s.
#include <benchmark/benchmark.h>

#include "bim/plan_parser.hpp"
#include "bim/polygon.hpp"
#include "bim/synthetic_plan.hpp"
#include "common/json_reader.hpp"
#include "sim/mujoco_world.hpp"
#include "sim/ray_caster.hpp"
#include "sim/scan_caster.hpp"
#include "sim/simulation.hpp"
#include "sim/vlp16.hpp"
#include "worlds/mjcf_generator.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

constexpr unsigned kGroups = (1u << worlds::kBuildingGroup) | (1u << worlds::kCeilingGroup);

struct Scene {
  bim::Scenario scenario;
  MujocoWorld world;
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> rays;  // origin, unit direction
  std::vector<Eigen::Vector2d> sensors;  // one per turn: the turn's rays are rays[28928·i …]
};

Scene makeScene(bim::Scenario scenario) {
  Scene scene{scenario, MujocoWorld::fromXml(worlds::generateMjcf(scenario)), {}, {}};
  const int sequences = Vlp16::sequencesPerTurn(10.0);
  const auto& rooms = scenario.plan.levels[0].rooms;
  // The sensor 0.71 m above the floor (0.46 m body + 0.25 m mount) at up to 8 room centroids.
  for (std::size_t r = 0; r < rooms.size() && r < 8; ++r) {
    const Eigen::Vector2d c = bim::centroid(rooms[r].outline);
    const Eigen::Vector3d sensor(c.x(), c.y(), 0.71);
    scene.sensors.push_back(c);
    for (int s = 0; s < sequences; ++s) {
      for (int l = 0; l < Vlp16::kLasers; ++l) {
        const double az = Vlp16::azimuth(Vlp16::firingTime(s, l), 10.0);
        scene.rays.emplace_back(sensor + Vlp16::origin(l), Vlp16::direction(l, az));
      }
    }
  }
  return scene;
}

const Scene& largestReference() {
  static const Scene scene =
      makeScene(worlds::loadScenarioOrBuiltin("builtin:d6.asbuilt", nullptr));
  return scene;
}

const Scene& grid200() {
  static const Scene scene = [] {
    const common::JsonSource source{"grid.json", nullptr};
    const nlohmann::json doc = bim::makeGridPlan({});
    bim::Scenario s;
    s.plan = bim::parsePlan(common::JsonNode(doc, "", source));
    return makeScene(s);
  }();
  return scene;
}

void castWithMjRay(benchmark::State& state, const Scene& scene) {
  const auto mask = groupArray(kGroups);
  const mjModel* m = &scene.world.model();
  const mjData* d = &scene.world.data();
  std::size_t hits = 0;
  for (auto _ : state) {
    for (const auto& [origin, dir] : scene.rays) {
      int geom = -1;
      hits += mj_ray(m, d, origin.data(), dir.data(), mask.data(), 1, -1, &geom) >= 0;
    }
  }
  state.SetItemsProcessed(state.iterations() * scene.rays.size());
  state.counters["geoms"] = m->ngeom;
  benchmark::DoNotOptimize(hits);
}

void castWithFastCaster(benchmark::State& state, const Scene& scene) {
  const RayCaster caster(scene.world.model(), scene.world.data(), kGroups);
  std::size_t hits = 0;
  for (auto _ : state) {
    for (const auto& [origin, dir] : scene.rays) hits += caster.cast(origin, dir).has_value();
  }
  state.SetItemsProcessed(state.iterations() * scene.rays.size());
  state.counters["geoms"] = scene.world.model().ngeom;
  benchmark::DoNotOptimize(hits);
}

// The scan path: prepared once per turn (included in the time), then every ray of the turn.
void castWithScanCaster(benchmark::State& state, const Scene& scene) {
  const RayCaster caster(scene.world.model(), scene.world.data(), kGroups);
  ScanCaster scan(caster);
  const std::size_t per_turn = scene.rays.size() / scene.sensors.size();
  std::size_t hits = 0;
  for (auto _ : state) {
    for (std::size_t t = 0; t < scene.sensors.size(); ++t) {
      scan.prepare(scene.sensors[t], 0.08);
      for (std::size_t i = t * per_turn; i < (t + 1) * per_turn; ++i) {
        hits += scan.cast(scene.rays[i].first, scene.rays[i].second).has_value();
      }
    }
  }
  state.SetItemsProcessed(state.iterations() * scene.rays.size());
  state.counters["geoms"] = scene.world.model().ngeom;
  benchmark::DoNotOptimize(hits);
}

void BM_MjRay_D6(benchmark::State& s) { castWithMjRay(s, largestReference()); }
void BM_FastCaster_D6(benchmark::State& s) { castWithFastCaster(s, largestReference()); }
void BM_MjRay_Grid200(benchmark::State& s) { castWithMjRay(s, grid200()); }
void BM_FastCaster_Grid200(benchmark::State& s) { castWithFastCaster(s, grid200()); }
void BM_ScanCaster_D6(benchmark::State& s) { castWithScanCaster(s, largestReference()); }
void BM_ScanCaster_Grid200(benchmark::State& s) { castWithScanCaster(s, grid200()); }
BENCHMARK(BM_MjRay_D6)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ScanCaster_D6)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ScanCaster_Grid200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FastCaster_D6)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MjRay_Grid200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FastCaster_Grid200)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace isg::sim

namespace isg::sim {
namespace {

// Whole VLP-16 turns as `isg simulate` makes them (poses, casting, noise, points) in D6 as built,
// on one thread. Real time is 10 turns per second: the real-time factor per thread is
// (turns per second) / 10.
void BM_SimulateTurn_D6(benchmark::State& state) {
  static Simulation sim(worlds::loadScenarioOrBuiltin("builtin:d6.asbuilt", nullptr));
  const auto lidar = sim.makeLidar();
  int k = 0;
  std::size_t points = 0;
  ScanTiming timing;
  for (auto _ : state) {
    const LidarScan scan = sim.scan(k++ % sim.scanCount(sim.duration()), *lidar);
    points += scan.points.size();
    timing += scan.timing;
  }
  state.SetItemsProcessed(state.iterations());
  // Each stage's share of a turn, in ms (means over the iterations).
  const double n = double(state.iterations());
  state.counters["poses_ms"] = 1e3 * timing.poses_s / n;
  state.counters["casting_ms"] = 1e3 * timing.casting_s / n;
  state.counters["noise_ms"] = 1e3 * timing.noise_s / n;
  state.counters["real_time_factor"] =
      benchmark::Counter(double(state.iterations()) / 10.0, benchmark::Counter::kIsRate);
  benchmark::DoNotOptimize(points);
}
BENCHMARK(BM_SimulateTurn_D6)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace isg::sim
