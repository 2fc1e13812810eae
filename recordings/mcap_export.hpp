#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "formats/mcap_writer.hpp"
#include "recordings/dataset_messages.hpp"

namespace isg::recordings {

struct McapExportOptions {
  // Whole seconds added to every dataset time, as the ROS 1 bag's (RosbagExportOptions); a ROS 2
  // stamp's seconds are an int32, so the sum stays below 2^31 s.
  std::uint32_t stamp_offset = 1000000000;
  formats::McapCompression compression = formats::McapCompression::kZstd;
  bool overwrite = false;
  // Clouds in the Velodyne driver's layout whatever the model (else the model's driver's:
  // exportCloudConvention).
  bool velodyne_layout = false;
};

// Writes a dataset folder (docs/formats.md, "Datasets") as an MCAP file of ROS 2 messages (CDR,
// ros2msg schemas): the same topics, frames, stamps and values as the ROS 1 bag of
// exportRosbag (docs/formats.md, "MCAP"). `progress(done, total)` is called after each scan. Bad
// input is an InputError naming the file; the file appears at `mcap_path` only when complete.
ExportSummary exportMcap(const std::string& dataset_dir, const std::string& mcap_path,
                         const McapExportOptions& options,
                         const std::function<void(int, int)>& progress);

}  // namespace isg::recordings
