#include "cli/cmd_simulate.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <vector>

#include "cli/cmd_export.hpp"
#include "cli/progress_bar.hpp"
#include "cli/route_check.hpp"
#include "common/atomic_folder.hpp"
#include "common/plural.hpp"
#include "sim/dataset_writer.hpp"
#include "sim/euroc_writer.hpp"
#include "sim/simulation.hpp"

namespace isg::cli {

SimulateCommand::SimulateCommand(CLI::App& parent) {
  app_ =
      parent.add_subcommand("simulate", "Synthesise a dataset: walk the robot, record its sensors");
  app_->footer(
      "The robot walks the scenario's route (default: a tour of every room reachable through "
      "open doors) in the building as built; its VLP-16 scans, its IMU, its odometry and the "
      "ground truth are written to DATASET_DIR: scans/NNNNNN.pcd, imu.csv, groundtruth.tum, "
      "odometry.tum, scans.tum, metadata.json (docs/formats.md). The same seed gives a "
      "byte-identical dataset. With --euroc the scenario's cameras are rendered along the walk "
      "(RGB, and depth where the model has it) into DATASET_DIR/mav0/ in the EuRoC layout, "
      "with each camera's ground truth (mav0/<camera>.tum, stamped as its images); --rosbag "
      "and --mcap then carry the images too.\n\n" +
      builtinWorldsHelp());
  app_->add_option("input", input_, "plan or scenario file, or builtin:NAME")
      ->option_text("PLAN|SCENARIO")
      ->required();
  app_->add_option("-o,--output", output_, "dataset folder to create")
      ->option_text("DATASET_DIR")
      ->required();
  app_->add_option("--seed", seed_, "seed for every random draw")
      ->check(seedNumber())
      ->default_str("the scenario's");
  addLidarModelOption(*app_, lidar_model_);
  app_->add_option("--duration", duration_, "seconds to simulate")
      ->default_str("the whole route")
      ->check(positiveNumber());
  app_->add_option("--threads", threads_, "threads casting scans")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  app_->add_option("--pcd", pcd_,
                   "how scans store their points: binary_compressed (LZF, as PCL writes it; about "
                   "0.8 of the size on simulated scans) or binary (uncompressed)")
      ->check(CLI::IsMember({"binary_compressed", "binary"}))
      ->capture_default_str();
  app_->add_option(
          "--rosbag", rosbag_,
          "also write the dataset as a ROS 1 bag (as isg export DATASET_DIR --rosbag does)")
      ->option_text("OUT.bag");
  CLI::Option* mcap = app_->add_option("--mcap", mcap_,
                                       "also write the dataset as an MCAP file of ROS 2 messages "
                                       "(as isg export DATASET_DIR --mcap does)")
                          ->option_text("OUT.mcap");
  addMcapCompressionOption(*app_, compression_, mcap);
  app_->add_option("--stamp-offset", stamp_offset_,
                   "with --rosbag / --mcap: whole seconds added to every dataset time there")
      ->check(CLI::Range(0u, 4000000000u))
      ->capture_default_str();
  addCloudLayoutOption(*app_, cloud_layout_);
  app_->add_flag(
      "--euroc", euroc_,
      "also render the scenario's cameras (\"cameras\") and write them, the IMU and the "
      "ground truth in the EuRoC layout: DATASET_DIR/mav0/ (docs/formats.md, \"EuRoC\")");
  app_->add_flag("--force", force_, "replace DATASET_DIR (and OUT.bag, OUT.mcap) if it exists");
  app_->add_flag("-q,--quiet", quiet_, "no progress bar");
}

bool SimulateCommand::optionsAgree() const {
  // Options about the recordings do nothing without one: said, as CLI11 says --compression's.
  const bool stamped = !rosbag_.empty() || !mcap_.empty() || euroc_;
  if (app_->count("--cloud-layout") > 0 && rosbag_.empty() && mcap_.empty()) {
    std::fprintf(stderr,
                 "isg: --cloud-layout requires --rosbag or --mcap (it lays out their "
                 "messages)\nRun 'isg --help' (or 'isg COMMAND --help') for usage.\n");
    return false;
  }
  if (app_->count("--stamp-offset") > 0 && !stamped) {
    std::fprintf(stderr,
                 "isg: --stamp-offset requires --rosbag, --mcap or --euroc (it stamps their "
                 "messages)\nRun 'isg --help' (or 'isg COMMAND --help') for usage.\n");
    return false;
  }
  return true;
}

void SimulateCommand::checkRecordingPaths() const {
  if (!rosbag_.empty()) {
    // Checked before hours of simulation, as the folder is: the bag may not be the scenario, nor
    // lie in the dataset it is made from.
    common::checkOutputPath(rosbag_,
                            {common::OutputKind::kBag, {inputFile(input_), output_}, force_});
    common::AtomicFile probe(rosbag_, common::OutputKind::kBag, force_);
  }
  if (!mcap_.empty()) {
    std::vector<std::string> inputs = {inputFile(input_), output_};
    if (!rosbag_.empty()) inputs.push_back(rosbag_);
    common::checkOutputPath(mcap_, {common::OutputKind::kMcap, inputs, force_});
    common::AtomicFile probe(mcap_, common::OutputKind::kMcap, force_);
  }
}

int SimulateCommand::run() {
  if (!optionsAgree()) return kExitUsage;
  bim::Scenario scenario = loadInput(input_, "simulate");
  if (seed_) scenario.seed = *seed_;
  useLidarModelOption(scenario, lidar_model_);
  if (euroc_ && scenario.cameras.empty()) {
    throw common::InputError(inputFile(input_), "/cameras",
                             "--euroc renders the scenario's cameras, and it has none (add "
                             "\"cameras\": [{\"model\": \"realsense-d435\"}], docs/formats.md)");
  }
  sim::Simulation simulation(scenario);
  checkRoute("isg simulate", scenario, simulation, duration_);
  common::checkCanCreateFolder(output_, common::OutputKind::kDataset, force_, {inputFile(input_)});
  checkRecordingPaths();
  sim::DatasetOptions options;
  options.duration = duration_;
  options.overwrite = force_;
  options.threads = threads_;
  options.pcd = pcd_ == "binary" ? formats::dataset::PcdData::kBinary
                                 : formats::dataset::PcdData::kBinaryCompressed;
  ProgressBar bar("isg simulate", quiet_);
  std::optional<sim::EurocSummary> euroc;
  if (euroc_) {
    // Rendered into the dataset's folder before it is renamed into place: the cameras land
    // with the scans, or nothing does.
    options.also_write = [&](const std::filesystem::path& folder) {
      bar.finish();
      euroc = writeEurocWithProgress(simulation, folder.string());
    };
  }
  const auto start = std::chrono::steady_clock::now();
  const double period = simulation.scanPeriod();
  const auto summary = sim::writeDataset(simulation, output_, options, [&](int done, int total) {
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    char detail[128];
    std::snprintf(detail, sizeof detail, "%d/%d scans, %.0f s simulated, %.1fx real time", done,
                  total, done * period, wall > 0 ? done * period / wall : 0.0);
    bar.update(total > 0 ? double(done) / total : 1.0, detail);
  });
  bar.finish();
  std::printf(
      "isg simulate: wrote %s: %s, %.2f M points (%.1f %% of %.2f M rays, %.0f MB of %s "
      "PCD), %.1f s of robot time in %.1f s (%.1fx real time), %s visited\n",
      output_.c_str(), common::counted(summary.scans, "scan").c_str(), summary.points / 1e6,
      summary.rays ? 100.0 * summary.points / summary.rays : 0.0, summary.rays / 1e6,
      summary.scan_bytes / 1e6, pcd_.c_str(), summary.sim_seconds, summary.wall_seconds,
      summary.wall_seconds > 0 ? summary.sim_seconds / summary.wall_seconds : 0.0,
      common::counted(simulation.route().visited_rooms.size(), "room").c_str());
  if (euroc) {
    std::printf(
        "isg simulate: wrote %s/mav0 (EuRoC): %s (%d with depth), %zu IMU samples, in %.1f s "
        "(%.1f frames/s)\n",
        output_.c_str(), common::counted(euroc->frames, "frame").c_str(), euroc->depth_frames,
        euroc->imu_samples, euroc->wall_seconds,
        euroc->wall_seconds > 0 ? euroc->frames / euroc->wall_seconds : 0.0);
  }
  // The command writes the dataset and its recordings, or nothing: when a recording cannot be
  // written (a full disk, Ctrl-C), what this run wrote before it goes again.
  std::vector<std::string> written = {output_};
  try {
    if (!rosbag_.empty()) {
      exportRosbagWithProgress("isg simulate", output_, rosbag_, stamp_offset_,
                               cloud_layout_ == "velodyne", force_, quiet_);
      written.push_back(rosbag_);
    }
    if (!mcap_.empty()) {
      exportMcapWithProgress("isg simulate", output_, mcap_, stamp_offset_,
                             cloud_layout_ == "velodyne", mcapCompression(compression_), force_,
                             quiet_);
    }
  } catch (...) {
    for (const auto& path : written) {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
    throw;
  }
  return kExitOk;
}

sim::EurocSummary SimulateCommand::writeEurocWithProgress(sim::Simulation& simulation,
                                                          const std::string& folder) {
  sim::EurocOptions options;
  options.duration = duration_;
  options.stamp_offset_s = stamp_offset_;
  ProgressBar bar("isg simulate --euroc", quiet_);
  const auto start = std::chrono::steady_clock::now();
  const auto summary = sim::writeEuroc(simulation, folder, options, [&](int done, int total) {
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    char detail[96];
    std::snprintf(detail, sizeof detail, "%d/%d frames, %.1f frames/s", done, total,
                  wall > 0 ? done / wall : 0.0);
    bar.update(total > 0 ? double(done) / total : 1.0, detail);
  });
  bar.finish();
  return summary;
}

}  // namespace isg::cli
