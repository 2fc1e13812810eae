#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "formats/dataset_format.hpp"
#include "sim/lidar_simulator.hpp"
#include "sim/simulation.hpp"

namespace isg::sim {

struct DatasetOptions {
  double duration = -1.0;  // seconds; < 0: the whole route
  double groundtruth_rate = 100.0;
  bool overwrite = false;  // replace an existing dataset folder
  int threads = 2;
  formats::dataset::PcdData pcd = formats::dataset::kDefaultPcdData;
  // Writes more into the dataset's folder while it is still the temporary one (the cameras'
  // EuRoC files): it lands with the rest or not at all.
  std::function<void(const std::filesystem::path& folder)> also_write;
};

struct DatasetSummary {
  double sim_seconds = 0.0;
  double wall_seconds = 0.0;
  int scans = 0;
  std::size_t points = 0;
  std::size_t rays = 0;
  std::size_t scan_bytes = 0;  // of scans/*.pcd, headers included
};

// Called from the writing thread as scans complete: (scans done, scans in all).
using ProgressCallback = std::function<void(int done, int total)>;

// Writes the dataset folder (sensors/dataset_format.hpp, docs/formats.md): scans/NNNNNN.pcd (PCD,
// DATA as options.pcd, fields x y z intensity ring time, LiDAR frame, not deskewed),
// groundtruth.tum (B_T_R), odometry.tum (M_T_R), scans.tum (B_T_L at each scan stamp) and
// metadata.json (and what options.also_write adds). Everything is written into a temporary folder
// beside `dir` and renamed into place at the end: a failed run leaves nothing behind. Errors about
// the folder are InputErrors naming it.
DatasetSummary writeDataset(Simulation& simulation, const std::string& dir,
                            const DatasetOptions& options, const ProgressCallback& progress);

}  // namespace isg::sim
