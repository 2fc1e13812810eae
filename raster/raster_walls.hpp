#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "common/occupancy_image.hpp"

namespace isg::raster {

using common::OccupancyImage;
using common::PixelClass;

// Walls, columns and doorways traced in an occupancy image (docs/formats.md, "Importing raster
// floor plans"). Every connected region of occupied pixels is one of:
//   - a speck (under `min_region_area`): noise, dropped and counted;
//   - a column: compact (at most `max_column_size` across, its pixels filling at least
//     `min_column_fill` of its oriented box, at most `max_column_aspect` long for its width),
//     rectangular or round (filling about π/4 of its box);
//   - a symbol (small and not compact: text, a door swing, a hatch mark): left out, said;
//   - walls: the region thinned to its skeleton, the skeleton's branches cut into straight runs
//     (Douglas–Peucker), each run's line and thickness fitted to the region's own extent across
//     it (the middle and width of the occupied run along the normal, sampled along the wall), its
//     ends closed against the walls it meets or carried to the region's edge at a free end.
//     Collinear runs are joined; a gap between two collinear walls where a person fits through
//     (`min_door_width` to `max_door_width`) is a doorway of the joined wall. Every patch of a
//     region's pixels that no wall found covers (curves, hatching, text touching a wall) is said.
// Coordinates here are the image's own, in metres: x along the columns from the image's left
// edge, y up from its bottom edge (row 0 is the top row).
struct RasterWallOptions {
  double resolution = 0.01;          // m a pixel
  double min_region_area = 0.0025;   // m²: smaller regions are specks
  double max_column_size = 1.5;      // m: the long side of a column's box
  double max_column_aspect = 2.5;    // long side over short side
  double min_column_fill = 0.7;      // of the oriented box
  double max_symbol_size = 0.6;      // m: smaller non-compact regions are symbols, not walls
  double min_door_width = 0.6;       // m: a person fits through
  double max_door_width = 2.5;       // m
  double collinear_angle = 1.5;      // degrees: runs this parallel may be one wall
  double min_uncovered_area = 0.02;  // m²: a patch of dark pixels no wall covers is said
  double min_wall_length = 0.05;     // m
  // Where the image lies in the plan, for the places messages name: its bottom-left corner, and
  // the image turned by `yaw` about it. The walls themselves stay in the image's own metres.
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double yaw = 0.0;
  // Called between regions and between the passes: a command stops the trace there by throwing
  // (its Ctrl-C), so no long image holds a user waiting. Nothing when empty.
  std::function<void()> check_interrupt;
};

struct RasterWall {
  Eigen::Vector2d start, end;  // the axis, in the image's metres
  double thickness = 0.0;
  enum class Kind { kWall, kColumn, kRoundColumn } kind = Kind::kWall;
};

struct RasterDoor {
  int wall = 0;         // index into RasterWalls::walls
  double offset = 0.0;  // centre of the opening from the wall's start, m
  double width = 0.0;
};

struct RasterWalls {
  std::vector<RasterWall> walls;  // columns included (kind)
  std::vector<RasterDoor> doors;
  std::vector<std::string> left_out;  // one line per region or part not turned into walls
  int regions = 0, specks = 0, symbols = 0;
};

RasterWalls traceRasterWalls(const OccupancyImage& image, const RasterWallOptions& options);

}  // namespace isg::raster
