#pragma once

#include <Eigen/Core>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bim/plan.hpp"
#include "raster/raster_walls.hpp"

namespace isg::raster {

// A floor plan image as a one-level plan (docs/formats.md, "Importing raster floor plans"): the
// walls and columns traced in it (raster/raster_walls.hpp), its doorways, and as rooms the free
// regions the walls enclose with the doors closed (bim/free_space_rooms.hpp). Columns are written
// as walls of their own footprint (named "column", "round column") until the plan format has
// columns. The image's bottom-left corner lies at `origin`, the image turned by `yaw` about it.
struct RasterPlanOptions {
  double resolution = 0.0;  // metres a pixel; required
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double yaw = 0.0;
  double height = 3.0;                    // the level's wall height
  double door_height = 2.1;               // at most 90 % of the wall height
  std::string source_kind = "image";      // for imported_from: "PNG image", "nav2 map", …
  std::string from_file;                  // the file named in imported_from (the YAML for a map)
  std::function<void()> check_interrupt;  // RasterWallOptions::check_interrupt
};

struct RasterPlanImport {
  bim::Plan plan;
  nlohmann::ordered_json plan_json;
  std::vector<std::string> log;  // regions left out or simplified, one line each
  int width = 0, height = 0;     // the image's pixels
  int walls = 0, columns = 0, doors = 0, rooms = 0, pockets = 0, specks = 0;
  // Doorways that join no rooms, written as gaps between wall parts instead of doors.
  int doorway_gaps = 0;
};

// Fails unless an image of `width` × `height` pixels at the options' resolution fits a level
// (docs/formats.md, Limits) and the options are in range: an InputError naming `file`. Checked on
// the image's header, before its pixels are decoded (formats::ImageSizeCheck), and again on the
// image given.
void checkImageExtent(long long width, long long height, const std::string& file,
                      const RasterPlanOptions& options);

// The plan from an image read by formats/raster_image.hpp (the round-trip tests draw one); the
// plan is read back by the plan's own parser before it is returned. Bad input (a floor beyond the
// plan's limits, no wall at all): InputError naming `image_path` (or options.from_file).
RasterPlanImport rasterPlanFromImage(const OccupancyImage& image, const std::string& image_path,
                                     const RasterPlanOptions& options);

}  // namespace isg::raster
