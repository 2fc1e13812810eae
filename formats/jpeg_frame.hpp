#pragma once

#include <string>

namespace isg::formats {

// The JPEG quality camera frames are exported at (libjpeg's 0–100 scale): the floor-plan
// benchmark's bags carry JPEG, and at 90 the textures' corners stay where they were (the
// exports' oracle counts them).
inline constexpr int kJpegQuality = 90;

// An 8-bit RGB PNG file (an EuRoC frame) of `width` × `height` as JPEG (libjpeg-turbo, 4:2:0,
// baseline): what sensor_msgs/CompressedImage carries. A file that is not such a PNG, or of
// another size than its camera's: a common::InputError naming it.
std::string rgbPngFileToJpeg(const std::string& png_path, int width, int height,
                             int quality = kJpegQuality);

}  // namespace isg::formats
