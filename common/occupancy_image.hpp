#pragma once

#include <cstdint>
#include <vector>

namespace isg::common {

// A floor plan image read into one class per pixel (formats/raster_image.hpp reads PNG, PGM and
// ROS maps into it; raster/raster_walls.hpp traces walls in it). Row 0 is the image's top row.
enum class PixelClass : std::uint8_t { kFree = 0, kOccupied = 1, kUnknown = 2 };

struct OccupancyImage {
  int width = 0, height = 0;
  std::vector<PixelClass> pixels;  // row-major, row 0 at the top
  PixelClass at(int column, int row) const { return pixels[std::size_t(row) * width + column]; }
};

}  // namespace isg::common
