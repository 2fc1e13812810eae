#include "cli/cmd_export.hpp"

#include <cstdio>
#include <filesystem>
#include <functional>
#include <vector>

#include "cli/progress_bar.hpp"
#include "common/input_error.hpp"
#include "common/output_path.hpp"
#include "recordings/mcap_export.hpp"
#include "recordings/rosbag_export.hpp"
#include "run/foxglove/run_mcap.hpp"

namespace isg::cli {

namespace {

// The progress bar's update after each scan, and after each camera image when the dataset has
// them (its mav0 folder, isg simulate --euroc: the exports carry its frames).
std::function<void(int, int)> scansTo(ProgressBar& bar, const std::string& dataset_dir) {
  const char* what = std::filesystem::is_directory(std::filesystem::path(dataset_dir) / "mav0")
                         ? "scans and images"
                         : "scans";
  return [&bar, what](int done, int total) {
    char detail[80];
    std::snprintf(detail, sizeof detail, "%d/%d %s", done, total, what);
    bar.update(total > 0 ? double(done) / total : 1.0, detail);
  };
}

// "topic n, topic n, ...": messages per topic, as the summaries print them.
template <typename Counts>
std::string countsText(const Counts& counts) {
  std::string text;
  for (const auto& [topic, n] : counts) {
    text += (text.empty() ? "" : ", ") + topic + " " + std::to_string(n);
  }
  return text;
}

void printExportSummary(const std::string& command, const std::string& path,
                        const recordings::ExportSummary& summary) {
  const std::string counts = countsText(summary.messages);
  std::printf("%s: wrote %s: %.0f MB, %.1f s of robot time in %.1f s (%.0f MB/s); messages: %s\n",
              command.c_str(), path.c_str(), summary.bytes / 1e6, summary.dataset_seconds,
              summary.wall_seconds,
              summary.wall_seconds > 0 ? summary.bytes / 1e6 / summary.wall_seconds : 0.0,
              counts.c_str());
  std::printf("%s: clouds in %s layout\n", command.c_str(), summary.cloud_layout.c_str());
}

}  // namespace

ExportCommand::ExportCommand(CLI::App& parent) {
  app_ = parent.add_subcommand(
      "export",
      "Write a dataset for other tools (a ROS 1 bag, an MCAP file of ROS 2 messages), or a run "
      "as an MCAP file to watch in Foxglove");
  app_->footer(
      "The bag (format 2.0, uncompressed; rosbag, rqt_bag and every ROS 1 tool read it) and the "
      "MCAP file (ROS 2 messages in CDR with their ros2msg schemas, chunked and indexed; ros2 bag, "
      "Foxglove and the mcap tools read it) hold "
      "/velodyne_points (sensor_msgs/PointCloud2 in the layout the LiDAR model's ROS driver "
      "publishes: x y z intensity ring time for the VLP models, Hesai's x y z intensity timestamp "
      "ring for pandar-xt32, ouster-ros's x y z intensity t reflectivity ring ambient range for "
      "the OS models, or Velodyne's for every model with --cloud-layout velodyne; frame "
      "velodyne, stamp = the scan's first firing), /imu/data "
      "(sensor_msgs/Imu, frame imu), /odom (nav_msgs/Odometry, odom → base_link), /tf "
      "(odom → base_link), /tf_static (base_link → velodyne, base_link → imu) and /ground_truth "
      "(nav_msgs/Odometry of base_link in the plan frame). A dataset written with --euroc also "
      "gives each camera of its mav0 folder: /<camera>/image_raw/compressed "
      "(sensor_msgs/CompressedImage: JPEG, depth as 16-bit PNG) and /<camera>/camera_info. "
      "Stamps are the dataset's times plus --stamp-offset. docs/formats.md (\"ROS bags\", "
      "\"Cameras in bags\", \"MCAP\").\n\n"
      "Given a run folder (isg run's or isg slam's output), --mcap writes the run as isg run "
      "--mcap does, from what the folder keeps: the plan, the A-Graph, the keyframes as they were "
      "made and the final S-Graph, matching, paths, transforms and deviations, but no scans "
      "(docs/foxglove.md).");
  app_->add_option("input", input_,
                   "dataset folder (isg simulate's output) or run folder (isg run's, isg slam's)")
      ->option_text("DATASET_DIR|RUN_DIR")
      ->required();
  app_->add_option("--rosbag", rosbag_, "the ROS 1 bag to write")->option_text("OUT.bag");
  CLI::Option* mcap = app_->add_option("--mcap", mcap_, "the MCAP file of ROS 2 messages to write")
                          ->option_text("OUT.mcap");
  addMcapCompressionOption(*app_, compression_, mcap);
  app_->add_option("--stamp-offset", stamp_offset_,
                   "whole seconds added to every dataset time (ROS reads a zero stamp as no time)")
      ->check(CLI::Range(0u, 4000000000u))
      ->capture_default_str();
  addCloudLayoutOption(*app_, cloud_layout_);
  app_->add_flag("--force", force_, "replace OUT.bag / OUT.mcap if it exists");
  app_->add_flag("-q,--quiet", quiet_, "no progress bar");
}

int ExportCommand::run() {
  if (run::isRunFolder(input_)) return exportRun();
  if (rosbag_.empty() && mcap_.empty()) {
    throw common::InputError("--rosbag, --mcap", "",
                             "nothing to write: give --rosbag OUT.bag, --mcap OUT.mcap or both");
  }
  if (!rosbag_.empty()) {
    common::checkOutputPath(rosbag_, {common::OutputKind::kBag, {input_}, force_});
  }
  if (!mcap_.empty()) {
    std::vector<std::string> inputs = {input_};
    if (!rosbag_.empty()) inputs.push_back(rosbag_);  // the two may not be one file
    common::checkOutputPath(mcap_, {common::OutputKind::kMcap, inputs, force_});
  }
  if (!rosbag_.empty()) {
    exportRosbagWithProgress("isg export", input_, rosbag_, stamp_offset_,
                             cloud_layout_ == "velodyne", force_, quiet_);
  }
  if (!mcap_.empty()) {
    exportMcapWithProgress("isg export", input_, mcap_, stamp_offset_, cloud_layout_ == "velodyne",
                           mcapCompression(compression_), force_, quiet_);
  }
  return kExitOk;
}

void printRunMcapSummary(const std::string& command, const std::string& path,
                         const std::vector<std::pair<std::string, std::uint64_t>>& counts) {
  std::error_code error;
  const auto bytes = std::filesystem::file_size(path, error);
  std::printf("%s: wrote %s: %.1f MB; messages: %s\n", command.c_str(), path.c_str(),
              error ? 0.0 : bytes / 1e6, countsText(counts).c_str());
}

int ExportCommand::exportRun() {
  if (!rosbag_.empty() || mcap_.empty()) {
    throw common::InputError(
        input_, "",
        "a run folder (it has metrics.json and estimate_map.tum) is written as "
        "--mcap OUT.mcap only; --rosbag takes a dataset folder");
  }
  common::checkOutputPath(mcap_, {common::OutputKind::kMcap, {input_}, force_});
  run::RunMcapOptions options;
  options.compression = mcapCompression(compression_);
  options.overwrite = force_;
  options.stamp_offset = stamp_offset_;
  const run::RunExportSummary summary = run::exportRunMcap(input_, mcap_, options);
  printRunMcapSummary("isg export", mcap_, summary.counts);
  return kExitOk;
}

formats::McapCompression mcapCompression(const std::string& name) {
  if (name == "none") return formats::McapCompression::kNone;
  if (name == "lz4") return formats::McapCompression::kLz4;
  return formats::McapCompression::kZstd;
}

void addMcapCompressionOption(CLI::App& app, std::string& compression, CLI::Option* mcap) {
  // Only with --mcap: alone it would be ignored, and the user would think it was applied.
  app.add_option("--compression", compression,
                 "with --mcap: how the MCAP file's chunks are compressed (zstd: smallest; lz4: "
                 "fastest to read)")
      ->check(CLI::IsMember({"none", "zstd", "lz4"}))
      ->needs(mcap)
      ->capture_default_str();
}

void addCloudLayoutOption(CLI::App& app, std::string& layout) {
  app.add_option("--cloud-layout", layout,
                 "the clouds' point layout: driver (the ROS driver's of the dataset's LiDAR "
                 "model: Velodyne's, Hesai's or ouster-ros's) or velodyne (the Velodyne driver's "
                 "whatever the model)")
      ->check(CLI::IsMember({"driver", "velodyne"}))
      ->capture_default_str();
}

void exportRosbagWithProgress(const std::string& command, const std::string& dataset_dir,
                              const std::string& bag_path, std::uint32_t stamp_offset,
                              bool velodyne_layout, bool overwrite, bool quiet) {
  recordings::RosbagExportOptions options;
  options.stamp_offset = stamp_offset;
  options.velodyne_layout = velodyne_layout;
  options.overwrite = overwrite;
  ProgressBar bar(command, quiet);
  const auto summary =
      recordings::exportRosbag(dataset_dir, bag_path, options, scansTo(bar, dataset_dir));
  bar.finish();
  printExportSummary(command, bag_path, summary);
}

void exportMcapWithProgress(const std::string& command, const std::string& dataset_dir,
                            const std::string& mcap_path, std::uint32_t stamp_offset,
                            bool velodyne_layout, formats::McapCompression compression,
                            bool overwrite, bool quiet) {
  recordings::McapExportOptions options;
  options.stamp_offset = stamp_offset;
  options.velodyne_layout = velodyne_layout;
  options.compression = compression;
  options.overwrite = overwrite;
  ProgressBar bar(command, quiet);
  const auto summary =
      recordings::exportMcap(dataset_dir, mcap_path, options, scansTo(bar, dataset_dir));
  bar.finish();
  printExportSummary(command, mcap_path, summary);
}

}  // namespace isg::cli
