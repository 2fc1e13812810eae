#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "sim/simulation.hpp"

namespace isg::sim {

struct EurocOptions {
  double duration = -1.0;  // seconds; < 0: the whole route
  // Whole seconds added to every simulated time: EuRoC stamps are nanoseconds of a clock, and
  // tools take 0 for "no stamp".
  std::uint64_t stamp_offset_s = 1000000000;
};

struct EurocSummary {
  int frames = 0;        // images written, every camera's (a depth image counted with its RGB)
  int depth_frames = 0;  // of them, with a depth image
  std::size_t imu_samples = 0;
  double wall_seconds = 0.0;
};

// Called as frames are written: (frames done, frames in all).
using FrameProgress = std::function<void(int done, int total)>;

// Renders the scenario's cameras along the simulated walk and writes them, the IMU and the
// ground truth in the EuRoC MAV layout under `dataset_dir` (docs/formats.md, "EuRoC"):
// mav0/<camera>/data/<ns>.png with data.csv and sensor.yaml, mav0/depth<k>/ (16-bit PNG in
// millimetres, registered to the camera), mav0/imu0/, mav0/state_groundtruth_estimate0/ (the IMU
// in B), mav0/camchain.yaml (Kalibr's camera chain) and mav0/<camera>.tum (B_T_C at each frame,
// stamped as its image, in seconds). mav0 is written in place and removed again if writing fails:
// the caller gives a folder that appears only when complete (isg simulate gives the dataset's
// temporary folder, DatasetOptions::also_write). Frames go to disk as they are made: memory does
// not grow with the walk. Throws std::invalid_argument when the scenario has no camera.
EurocSummary writeEuroc(Simulation& simulation, const std::string& dataset_dir,
                        const EurocOptions& options, const FrameProgress& progress);

}  // namespace isg::sim
