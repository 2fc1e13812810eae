#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>

#include "recordings/dataset_messages.hpp"

namespace isg::recordings {

struct RosbagExportOptions {
  // Whole seconds added to every dataset time: ROS reads a zero stamp as "no time" (tf's
  // "latest"), so dataset time 0 becomes 1000000000 s (2001-09-09), and bag time T is dataset
  // time T − 1e9.
  std::uint32_t stamp_offset = 1000000000;
  bool overwrite = false;
  // Clouds in the Velodyne driver's layout whatever the model (else the model's driver's:
  // exportCloudConvention).
  bool velodyne_layout = false;
};

// Writes a dataset folder (docs/formats.md, "Datasets") as a ROS 1 bag: every scan, IMU sample,
// odometry and ground-truth pose, and the transforms between the frames. `progress(done, total)`
// is called after each scan. Bad input is an InputError naming the file; the bag appears at
// `bag_path` only when complete.
ExportSummary exportRosbag(const std::string& dataset_dir, const std::string& bag_path,
                           const RosbagExportOptions& options,
                           const std::function<void(int, int)>& progress);

}  // namespace isg::recordings
