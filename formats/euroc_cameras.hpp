#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "formats/camera_calibration.hpp"

namespace isg::formats {

// The camera streams of a dataset's EuRoC folder (DATASET/mav0, written by isg simulate --euroc;
// docs/formats.md, "EuRoC (cameras)"), read back for the ROS 1 bag and MCAP exports.

struct EurocFrame {
  std::int64_t stamp_ns = 0;  // EuRoC's stamp (the simulation's time plus a whole-second offset)
  double t = 0.0;             // seconds of the simulation, the dataset's clock
  std::string path;           // the image file
};

struct EurocCamera {
  std::string name;    // its folder under mav0: "cam0", "depth0", …
  bool depth = false;  // 16-bit PNG in millimetres (sensor.yaml has depth_scale_m), else RGB
  double rate_hz = 0.0;
  Eigen::Isometry3d I_T_C = Eigen::Isometry3d::Identity();  // sensor.yaml's T_BS
  CameraCalibration calibration;
  std::vector<EurocFrame> frames;
};

// Every folder under DATASET/mav0 whose sensor.yaml says `sensor_type: camera`, by name, with its
// frames from data.csv. The EuRoC stamps carry a whole-second offset (isg simulate
// --stamp-offset); it is found from mav0/imu0 (the dataset's IMU samples with EuRoC stamps)
// against `first_imu_t`, the dataset's first IMU time, and taken off every stamp, so that the
// frames share the dataset's clock. Empty when the dataset has no mav0 folder or no camera in
// it. Malformed files, frames without their image, an IMU folder that does not match, or depth
// folders alone: a common::InputError naming the file and what is wrong.
std::vector<EurocCamera> readEurocCameras(const std::string& dataset_dir, double first_imu_t);

// A depth frame's file as it goes into a bag (lossless): its bytes, checked to be a PNG of 16-bit
// grey of `width` × `height` (its header, read by libpng), else a common::InputError naming it.
std::string readDepthPng(const std::string& path, int width, int height);

}  // namespace isg::formats
