#pragma once

#include <string>

namespace isg::formats {

// A camera frame's image at `path` is `width` × `height` pixels: its camera's `camera_width` ×
// `camera_height`, else a common::InputError naming the file ("is 8 x 6 pixels, its camera
// 640 x 480"). Shared by the colour and the depth frames' readers, so that both say it alike.
void requireFrameSize(const std::string& path, long width, long height, int camera_width,
                      int camera_height);

}  // namespace isg::formats
