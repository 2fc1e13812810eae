// libFuzzer harness: bytes → a small occupancy image (two bytes its width and height, 1–128
// pixels each, then one bit a pixel: 1 occupied) → the walls, columns and doorways traced in it
// and the plan they make (raster/raster_plan.hpp). Any InputError is the expected answer (an image
// with no wall); anything else (a crash, a sanitizer report, another exception) is a bug.
#include <cstdint>
#include <string>

#include "common/input_error.hpp"
#include "raster/raster_plan.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  isg::common::OccupancyImage image;
  image.width = 1 + data[0] % 128;
  image.height = 1 + data[1] % 128;
  image.pixels.assign(std::size_t(image.width) * image.height, isg::common::PixelClass::kFree);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    const std::size_t byte = 2 + i / 8;
    if (byte < size && ((data[byte] >> (i % 8)) & 1)) {
      image.pixels[i] = isg::common::PixelClass::kOccupied;
    }
  }
  try {
    isg::raster::RasterPlanOptions options;
    options.resolution = 0.02;
    isg::raster::rasterPlanFromImage(image, "fuzz.png", options);
  } catch (const isg::common::InputError&) {
  }
  return 0;
}
