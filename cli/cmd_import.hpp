#pragma once

#include <string>
#include <vector>

#include "cli/common.hpp"

namespace isg::cli {

// isg import MODEL.ifc -o PLAN.json: an IFC building model as a plan (docs/formats.md,
// "Importing IFC"); isg import FLOOR.png|.pgm|MAP.yaml -o PLAN.json: a raster floor plan as a
// plan ("Importing raster floor plans"); isg import RECORDING.bag -o DATASET_DIR: a robot's ROS 1
// recording as a dataset (docs/formats.md, "Importing recordings").
class ImportCommand : public Command {
 public:
  explicit ImportCommand(CLI::App& parent);
  int run() override;

 private:
  // The option table, by group (the constructor adds the rest).
  void addRasterOptions();
  void addRecordingOptions();
  int importIfc();
  int importBag();
  int importRaster();

  std::string input_;
  std::string output_;
  std::vector<std::string> storeys_;
  bool force_ = false;
  bool quiet_ = false;
  // Recordings.
  std::string lidar_topic_, imu_topic_, odometry_topic_, ground_truth_topic_, base_frame_,
      odometry_frame_;
  double start_ = 0.0, duration_ = 0.0;
  std::vector<double> lidar_extrinsic_, imu_extrinsic_;
  // Raster floor plans.
  double resolution_ = 0.0, wall_height_ = 3.0;
  std::vector<double> origin_;
};

}  // namespace isg::cli
