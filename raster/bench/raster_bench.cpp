// Raster floor plans: a generated floor of 200 rooms (80 m × 35 m) drawn at 1 cm a pixel
// (8000 × 3500 pixels, about the Hilti challenge's 7351 × 4206), traced into walls, and the whole
// import (walls, rooms from the free space, the plan read back). The rooms alone are the
// reference: the IFC import's free-space rooms on the same level.
#include <benchmark/benchmark.h>

#include "bim/free_space_rooms.hpp"
#include "bim/plan_parser.hpp"
#include "bim/synthetic_plan.hpp"
#include "common/json_reader.hpp"
#include "raster/raster_plan.hpp"
#include "raster/raster_walls.hpp"
#include "raster/tests/raster_drawing.hpp"

namespace isg::raster {
namespace {

using bim::FreeSpaceRooms;
using bim::GridPlanSpec;
using bim::Plan;
using bim::parsePlan;

struct DrawnFloor {
  Plan plan;
  OccupancyImage image;
  Eigen::Vector2d origin;
};

const DrawnFloor& floor200() {
  static const DrawnFloor drawn = [] {
    DrawnFloor out;
    GridPlanSpec spec;
    spec.rows = 10;
    spec.cols = 20;
    const common::JsonSource source{"grid.json", nullptr};
    out.plan = parsePlan(common::JsonNode(makeGridPlan(spec), "", source));
    out.image = testing::drawLevel(out.plan.levels[0], 0.01, 0.5, &out.origin);
    return out;
  }();
  return drawn;
}

void BM_RasterTraceWalls_Grid200(benchmark::State& state) {
  const DrawnFloor& drawn = floor200();
  RasterWallOptions options;
  for (auto _ : state) {
    RasterWalls walls = traceRasterWalls(drawn.image, options);
    benchmark::DoNotOptimize(walls);
  }
  state.counters["megapixels"] = double(drawn.image.pixels.size()) * 1e-6;
}
BENCHMARK(BM_RasterTraceWalls_Grid200)->Unit(benchmark::kMillisecond);

void BM_RasterImport_Grid200(benchmark::State& state) {
  const DrawnFloor& drawn = floor200();
  RasterPlanOptions options;
  options.resolution = 0.01;
  options.origin = drawn.origin;
  for (auto _ : state) {
    RasterPlanImport result = rasterPlanFromImage(drawn.image, "grid.png", options);
    benchmark::DoNotOptimize(result);
  }
}
BENCHMARK(BM_RasterImport_Grid200)->Unit(benchmark::kMillisecond);

void BM_FreeSpaceRooms_Grid200(benchmark::State& state) {
  const DrawnFloor& drawn = floor200();
  for (auto _ : state) {
    FreeSpaceRooms rooms = enclosedFreeSpaces(drawn.plan.levels[0]);
    benchmark::DoNotOptimize(rooms);
  }
}
BENCHMARK(BM_FreeSpaceRooms_Grid200)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace isg::raster
