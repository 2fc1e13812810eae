#pragma once

#include <cstdint>
#include <string>

#include "cli/common.hpp"

namespace isg::cli {

// isg export DATASET_DIR --rosbag OUT.bag: a dataset as a ROS 1 bag.
class ExportCommand : public Command {
 public:
  explicit ExportCommand(CLI::App& parent);
  int run() override;

 private:
  std::string input_;
  std::string rosbag_;
  std::uint32_t stamp_offset_ = 1000000000;
  bool force_ = false;
  bool quiet_ = false;
};

// Writes `dataset_dir` as a bag with a progress bar and prints what it wrote (shared by
// `isg export` and `isg simulate --rosbag`).
void exportRosbagWithProgress(const std::string& command, const std::string& dataset_dir,
                              const std::string& bag_path, std::uint32_t stamp_offset,
                              bool overwrite, bool quiet);

}  // namespace isg::cli
