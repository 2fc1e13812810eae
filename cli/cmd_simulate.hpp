#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "cli/common.hpp"

#include "sim/euroc_writer.hpp"

namespace isg::cli {

// isg simulate PLAN|SCENARIO -o DATASET_DIR [--seed N] [--duration S] [--pcd DATA]
// [--rosbag OUT.bag] [--mcap OUT.mcap] [--euroc]: synthesise a dataset (and a bag, an MCAP file,
// the cameras in the EuRoC layout).
class SimulateCommand : public Command {
 public:
  explicit SimulateCommand(CLI::App& parent);
  int run() override;

 private:
  std::string input_;
  std::string output_;
  std::optional<std::uint64_t> seed_;
  std::string lidar_model_;
  double duration_ = -1.0;
  int threads_ = 2;
  std::string pcd_ = "binary_compressed";
  std::string rosbag_;  // also write the dataset as this bag
  std::string mcap_;    // and as this MCAP file
  std::string compression_ = "zstd";
  std::string cloud_layout_ = "driver";
  std::uint32_t stamp_offset_ = 1000000000;
  bool euroc_ = false;  // also render the cameras into DATASET_DIR/mav0 (EuRoC)
  bool force_ = false;
  bool quiet_ = false;

  // Options about the recordings do nothing without one: false, said as CLI11 says
  // --compression's, when one is given without them.
  bool optionsAgree() const;
  // The bag and MCAP file may be written (checked before hours of simulation).
  void checkRecordingPaths() const;
  // The cameras into `folder`/mav0 (the dataset's folder while it is written), with a progress
  // bar of frames per second.
  sim::EurocSummary writeEurocWithProgress(sim::Simulation& simulation, const std::string& folder);
};

}  // namespace isg::cli
