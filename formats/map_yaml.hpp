#pragma once

#include <string>

#include "formats/raster_image.hpp"

namespace isg::formats {

// A ROS occupancy map's YAML file, as nav2's map_server (and ROS 1's map_server) read it
// (docs/formats.md, "Importing raster floor plans"):
//   image: floor.pgm           # relative to the YAML file's folder unless absolute
//   resolution: 0.05           # metres a pixel
//   origin: [x, y, yaw]        # the pose of the image's bottom-left corner in the map frame
//   negate: 0                  # 0/1 or true/false
//   occupied_thresh: 0.65
//   free_thresh: 0.25
//   mode: trinary              # optional: trinary (default), scale or raw
// image, resolution, origin, negate, occupied_thresh and free_thresh are required, as map_server
// requires them; other keys are ignored. Only this flat form of YAML is read: one `key: value`
// a line, `#` comments, the origin as a flow sequence.
struct MapYaml {
  std::string image;  // resolved against the YAML file's folder
  double resolution = 0.0;
  double origin_x = 0.0, origin_y = 0.0, origin_yaw = 0.0;
  OccupancyRule rule;
};

// Errors name the file, the key (as a JSON pointer, "/resolution") and the line.
MapYaml readMapYaml(const std::string& path);
MapYaml parseMapYaml(const std::string& text, const std::string& path);

}  // namespace isg::formats
