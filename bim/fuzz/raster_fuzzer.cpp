// libFuzzer harness: bytes → a floor plan image or a ROS map's YAML (the first byte chooses), and
// for a small accepted image what `isg import` does next: the walls traced in it. Any InputError
// is the expected answer to a bad file; anything else (a crash, a sanitizer report, another
// exception) is a bug.
#include <cstdint>
#include <string>

#include "bim/map_yaml.hpp"
#include "bim/raster_image.hpp"
#include "bim/raster_walls.hpp"
#include "common/input_error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    if (data[0] & 1) {
      isg::bim::parseMapYaml(bytes, "fuzz.yaml");
    } else {
      isg::bim::OccupancyRule rule;
      rule.mode = isg::bim::OccupancyRule::Mode((data[0] >> 1) % 3);
      rule.negate = (data[0] >> 3) & 1;
      const isg::bim::OccupancyImage image = isg::bim::decodeOccupancyImage(bytes, "fuzz", rule);
      if (image.pixels.size() <= 512 * 512) {
        isg::bim::RasterWallOptions options;
        options.resolution = 0.01;
        isg::bim::traceRasterWalls(image, options);
      }
    }
  } catch (const isg::common::InputError&) {
  }
  return 0;
}
