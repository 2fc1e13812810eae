#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <string>

#include "bim/scenario.hpp"

namespace isg::cli {

// A replayed walk's recording as the floor-plan benchmark's files name and time it: what a start
// pose table's row and a submission need of the run (docs/benchmark.md).
struct RecordingFrame {
  std::string sequence;      // the walk file's name without its extension: the run's name
  double clock_start = 0.0;  // the recording's clock at the run's t = 0 (its first stamp)
  // The frame the walk file tracks, on the base: the sensor's (R_T_L · (S_T_L)⁻¹ through the
  // route's rig) for a sensor's path, the base itself for a body's.
  Eigen::Isometry3d R_T_S = Eigen::Isometry3d::Identity();
  // A body's path: the walk's poses are the simulated carrier's, which faces along its travel
  // and glances about as it walks (sim/base_motion.hpp); a camera's orientation in the file says
  // nothing of that, so a pose given in the file's frame keeps its position and takes the
  // simulated body's heading at its stamp.
  bool body_path = false;
};

// Empty unless the scenario's route is a recorded walk ("trajectory").
std::optional<RecordingFrame> recordingFrameOf(const bim::Scenario& scenario);

}  // namespace isg::cli
