#include "formats/frame_size.hpp"

#include "common/input_error.hpp"

namespace isg::formats {

void requireFrameSize(const std::string& path, long width, long height, int camera_width,
                      int camera_height) {
  if (width == camera_width && height == camera_height) return;
  throw common::InputError(path, "",
                           "is " + std::to_string(width) + " x " + std::to_string(height) +
                               " pixels, its camera " + std::to_string(camera_width) + " x " +
                               std::to_string(camera_height));
}

}  // namespace isg::formats
