#include "cli/cmd_export.hpp"

#include <cstdio>

#include "cli/progress_bar.hpp"
#include "sensors/output_path.hpp"
#include "sensors/rosbag_export.hpp"

namespace isg::cli {

ExportCommand::ExportCommand(CLI::App& parent) {
  app_ = parent.add_subcommand("export", "Write a dataset for other tools: a ROS 1 bag");
  app_->footer(
      "The bag (format 2.0, uncompressed; rosbag, rqt_bag and every ROS 1 tool read it) holds "
      "/velodyne_points (sensor_msgs/PointCloud2: x y z intensity ring time, as the Velodyne "
      "driver publishes them, frame velodyne, stamp = the scan's first firing), /imu/data "
      "(sensor_msgs/Imu, frame imu), /odom (nav_msgs/Odometry, odom → base_link), /tf "
      "(odom → base_link), /tf_static (base_link → velodyne, base_link → imu) and /ground_truth "
      "(nav_msgs/Odometry of base_link in the plan frame). Stamps are the dataset's times plus "
      "--stamp-offset. docs/formats.md (\"ROS bags\").");
  app_->add_option("dataset", input_, "dataset folder (isg simulate's output)")
      ->option_text("DATASET_DIR")
      ->required();
  app_->add_option("--rosbag", rosbag_, "the bag to write")->option_text("OUT.bag")->required();
  app_->add_option("--stamp-offset", stamp_offset_,
                   "whole seconds added to every dataset time (ROS reads a zero stamp as no time)")
      ->check(CLI::Range(0u, 4000000000u))
      ->capture_default_str();
  app_->add_flag("--force", force_, "replace OUT.bag if it exists");
  app_->add_flag("-q,--quiet", quiet_, "no progress bar");
}

int ExportCommand::run() {
  sensors::checkOutputPath(rosbag_, {sensors::OutputKind::kBag, {input_}, force_});
  exportRosbagWithProgress("isg export", input_, rosbag_, stamp_offset_, force_, quiet_);
  return kExitOk;
}

void exportRosbagWithProgress(const std::string& command, const std::string& dataset_dir,
                              const std::string& bag_path, std::uint32_t stamp_offset,
                              bool overwrite, bool quiet) {
  sensors::RosbagExportOptions options;
  options.stamp_offset = stamp_offset;
  options.overwrite = overwrite;
  ProgressBar bar(command, quiet);
  const auto summary =
      sensors::exportRosbag(dataset_dir, bag_path, options, [&](int done, int total) {
        char detail[64];
        std::snprintf(detail, sizeof detail, "%d/%d scans", done, total);
        bar.update(total > 0 ? double(done) / total : 1.0, detail);
      });
  bar.finish();
  std::string counts;
  for (const auto& [topic, n] : summary.messages) {
    counts += (counts.empty() ? "" : ", ") + topic + " " + std::to_string(n);
  }
  std::printf("%s: wrote %s: %.0f MB, %.1f s of robot time in %.1f s (%.0f MB/s); messages: %s\n",
              command.c_str(), bag_path.c_str(), summary.bytes / 1e6, summary.dataset_seconds,
              summary.wall_seconds,
              summary.wall_seconds > 0 ? summary.bytes / 1e6 / summary.wall_seconds : 0.0,
              counts.c_str());
}

}  // namespace isg::cli
