// libFuzzer harness: bytes → a floor plan image (PNG or PGM) or a ROS map's YAML; the first byte
// chooses which, and the image's classing rule. Any InputError is the expected answer to a bad
// file; anything else (a crash, a sanitizer report, another exception) is a bug.
#include <cstdint>
#include <string>

#include "common/input_error.hpp"
#include "formats/map_yaml.hpp"
#include "formats/raster_image.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    if (data[0] & 1) {
      isg::formats::parseMapYaml(bytes, "fuzz.yaml");
    } else {
      isg::formats::OccupancyRule rule;
      rule.mode = isg::formats::OccupancyRule::Mode((data[0] >> 1) % 3);
      rule.negate = (data[0] >> 3) & 1;
      isg::formats::decodeOccupancyImage(bytes, "fuzz", rule);
    }
  } catch (const isg::common::InputError&) {
  }
  return 0;
}
