// Frames per second of each camera model, rendered as `isg simulate --euroc` renders them (D1,
// textured surfaces, the walk's poses) on the CPU through Mesa, the PNG writing left out
// (docs/sensors.md, "Speed"). Reported as frames per second; compare models within one run.
#include <benchmark/benchmark.h>

#include "sensors/mount_transform.hpp"
#include "sim/fisheye_camera.hpp"
#include "sim/renderer.hpp"
#include "sim/simulation.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::sim {
namespace {

Simulation d1WithCameras(const char* cameras) {
  bim::Scenario scenario = worlds::loadScenarioOrBuiltin("builtin:d1", nullptr);
  const nlohmann::json document = common::parseJsonText(cameras, "cameras.json");
  const common::JsonSource source{"cameras.json", nullptr};
  scenario.cameras = bim::parseCameras(common::JsonNode(document, "", source));
  return Simulation(scenario);
}

// A pinhole camera (the D435's RGB and depth, or the generic one) along the first 30 s.
void pinholeFrames(benchmark::State& state, const char* cameras, bool depth) {
  Simulation sim = d1WithCameras(cameras);
  const bim::CameraConfig& camera = sim.scenario().cameras[0];
  const bim::PinholeIntrinsics& k = camera.model.intrinsics;
  Renderer renderer(sim.world().model(), k.width, k.height, Renderer::Sampling::kPixelCentres);
  renderer.enableSurfaceTextures(1);
  const Eigen::Isometry3d R_T_C = sensors::mountTransform(camera.mount);
  std::vector<float> range;
  int frame = 0;
  for (auto _ : state) {
    const double t = (frame++ % 900) / 30.0;
    benchmark::DoNotOptimize(renderer.camera(sim.world().data(), sim.baseMotion().pose(t) * R_T_C,
                                             k, 15.0, depth ? &range : nullptr));
  }
  state.counters["frames_per_s"] =
      benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_RealsenseD435_RgbAndDepth(benchmark::State& state) {
  pinholeFrames(state, R"([{"model": "realsense-d435"}])", true);
}
BENCHMARK(BM_RealsenseD435_RgbAndDepth)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Pinhole_640x480_Rgb(benchmark::State& state) {
  pinholeFrames(state, R"([{"model": "pinhole"}])", false);
}
BENCHMARK(BM_Pinhole_640x480_Rgb)->Unit(benchmark::kMillisecond)->UseRealTime();

// One lens of the 360° rig, 1472 × 1440 through its cube map (the rig's frame is two of these).
void BM_Insta360OneRs_OneLens(benchmark::State& state) {
  Simulation sim = d1WithCameras(R"([{"model": "insta360-one-rs"}])");
  const bim::CameraConfig& lens = sim.scenario().cameras[0];
  FisheyeCamera camera(sim.world().model(), lens.model, 1);
  const Eigen::Isometry3d R_T_C = sim.R_T_I() * *lens.I_T_C;
  int frame = 0;
  for (auto _ : state) {
    const double t = (frame++ % 900) / 30.0;
    benchmark::DoNotOptimize(
        camera.render(sim.world().data(), sim.baseMotion().pose(t) * R_T_C, 50.0, nullptr));
  }
  state.counters["frames_per_s"] =
      benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Insta360OneRs_OneLens)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace isg::sim
