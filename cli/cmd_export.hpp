#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "cli/common.hpp"
#include "formats/mcap_writer.hpp"

namespace isg::cli {

// isg export DATASET_DIR --rosbag OUT.bag | --mcap OUT.mcap: a dataset as a ROS 1 bag, an MCAP
// file of ROS 2 messages, or both; isg export RUN_DIR --mcap OUT.mcap: a finished run as the MCAP
// file `isg run --mcap` writes (docs/foxglove.md).
class ExportCommand : public Command {
 public:
  explicit ExportCommand(CLI::App& parent);
  int run() override;

 private:
  int exportRun();

  std::string input_;
  std::string rosbag_;
  std::string mcap_;
  std::string compression_ = "zstd";
  std::string cloud_layout_ = "driver";
  std::uint32_t stamp_offset_ = 1000000000;
  bool force_ = false;
  bool quiet_ = false;
};

// Writes `dataset_dir` as a bag with a progress bar and prints what it wrote (shared by
// `isg export` and `isg simulate --rosbag`).
void exportRosbagWithProgress(const std::string& command, const std::string& dataset_dir,
                              const std::string& bag_path, std::uint32_t stamp_offset,
                              bool velodyne_layout, bool overwrite, bool quiet);
// The same as an MCAP file (shared by `isg export --mcap` and `isg simulate --mcap`).
void exportMcapWithProgress(const std::string& command, const std::string& dataset_dir,
                            const std::string& mcap_path, std::uint32_t stamp_offset,
                            bool velodyne_layout, formats::McapCompression compression,
                            bool overwrite, bool quiet);
// --cloud-layout driver|velodyne: which layout the exported clouds take (`layout` keeps the
// choice; "velodyne" is velodyne_layout above).
void addCloudLayoutOption(CLI::App& app, std::string& layout);
// Prints what a run's MCAP file holds: its size and the messages per topic.
void printRunMcapSummary(const std::string& command, const std::string& path,
                         const std::vector<std::pair<std::string, std::uint64_t>>& counts);
// "none", "zstd" or "lz4" as the command line spells it.
formats::McapCompression mcapCompression(const std::string& name);
// The --compression option of a command that writes MCAP.
void addMcapCompressionOption(CLI::App& app, std::string& compression, CLI::Option* mcap);

}  // namespace isg::cli
