#pragma once

#include <array>
#include <string>
#include <vector>

namespace isg::formats {

// A camera's calibration as sensor_msgs/CameraInfo carries it (ROS 1 and ROS 2 alike): the
// image size, the distortion model by ROS's name ("plumb_bob" with five coefficients,
// "equidistant" with k1–k4), K, and the projection P of the unrectified camera. Pixel
// coordinates as OpenCV's: (0, 0) is the top-left pixel's centre.
struct CameraCalibration {
  int width = 0;
  int height = 0;
  std::string distortion_model = "plumb_bob";
  std::vector<double> distortion;
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;

  std::array<double, 9> K() const { return {fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0}; }
  std::array<double, 9> R() const { return {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0}; }
  std::array<double, 12> P() const {
    return {fx, 0.0, cx, 0.0, 0.0, fy, cy, 0.0, 0.0, 0.0, 1.0, 0.0};
  }
};

}  // namespace isg::formats
