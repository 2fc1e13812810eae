#include "cli/cmd_import.hpp"

#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "bim/limits.hpp"
#include "cli/progress_bar.hpp"
#include "common/atomic_folder.hpp"
#include "common/output_path.hpp"
#include "common/plural.hpp"
#include "formats/map_yaml.hpp"
#include "formats/raster_image.hpp"
#include "formats/recording.hpp"
#include "ifc/ifc_import.hpp"
#include "raster/raster_plan.hpp"
#include "recordings/bag_import.hpp"
#include "run/interrupt.hpp"

namespace isg::cli {
namespace {

// Numbers to the micrometre: a plan a person can read and diff, far below any tolerance.
void roundNumbers(nlohmann::ordered_json& value) {
  if (value.is_number_float()) {
    const double rounded = std::round(value.get<double>() * 1e6) / 1e6;
    value = rounded == 0.0 ? 0.0 : rounded;
  } else if (value.is_structured()) {
    for (auto& child : value) roundNumbers(child);
  }
}

std::string lowerExtension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

bool isRecording(const std::string& path) { return formats::isRecordingPath(path); }
bool isRasterImage(const std::string& path) {
  const std::string extension = lowerExtension(path);
  return extension == ".png" || extension == ".pgm";
}
bool isMapYaml(const std::string& path) {
  const std::string extension = lowerExtension(path);
  return extension == ".yaml" || extension == ".yml";
}

std::optional<std::array<double, 6>> mountOption(const std::vector<double>& values) {
  if (values.empty()) return std::nullopt;
  return std::array<double, 6>{values[0], values[1], values[2], values[3], values[4], values[5]};
}

}  // namespace

ImportCommand::ImportCommand(CLI::App& parent) {
  app_ = parent.add_subcommand(
      "import",
      "Import an IFC building model (IFC2X3, IFC4) or a raster floor plan (PNG, PGM, a ROS map's "
      "YAML) as a plan, or a robot's recording (a ROS 1 .bag; a ROS 2 bag: its folder, a .db3 or "
      "an .mcap) as a dataset");
  app_->footer(
      "Storeys become levels (by default every storey with walls standing on it and rooms), "
      "walls straight prismatic walls fitted to their bodies, doors and windows their openings "
      "in the walls, spaces rooms (their outline is the bottom of their body). Ids are the IFC "
      "GlobalIds, names the IFC names. Every element left out or simplified gets one line saying "
      "which and why; a summary per storey ends the output. The plan is checked with the plan "
      "format's rules before it is written; nothing is written when the model cannot be read. "
      "IFC++ reads the model in a child process: a model that makes it crash is reported like any "
      "bad model (exit code 1). The rules and their thresholds: docs/formats.md, \"Importing "
      "IFC\".\n\n"
      "Example (ifc/tests/models holds five public models):\n"
      "  isg import Office_A_20110811.ifc -o office.json\n  isg check office.json -v\n"
      "  isg run office.json -o runs/office\n\n"
      "A recording — a ROS 1 bag (format 2.0; chunks plain, bz2 or lz4), a ROS 2 bag (rosbag2's "
      "folder with its metadata.yaml, split files in order, in the sqlite3 or the MCAP storage; "
      "or one .db3), or an MCAP file (CDR with ros2msg schemas, or ROS 1 messages; chunks plain, "
      "zstd or lz4) — becomes a dataset folder that isg slam replays: the point clouds "
      "(sensor_msgs/PointCloud2: the Velodyne driver's layout, Ouster's, "
      "or any cloud with x y z; Hesai's and Livox's times since the epoch too) as scans, "
      "sensor_msgs/Imu as imu.csv, nav_msgs/Odometry (or the "
      "transforms on /tf from a frame named odom down to the base) as odometry.tum, a ground-truth "
      "nav_msgs/Odometry or geometry_msgs/PoseStamped as "
      "groundtruth.tum; the sensors' mounts from /tf_static (or --lidar-extrinsic, "
      "--imu-extrinsic). Each topic is found by its type when only one could be it (ground truth "
      "by a name with ground_truth, groundtruth, gt, vicon or mocap); otherwise the candidates are "
      "listed. A bag written by isg export imports back to the dataset it came from; a recording "
      "without odometry is replayed with odometry made from its LiDAR and IMU. The rules: "
      "docs/formats.md, \"Importing recordings\".\n\n"
      "A raster floor plan (FLOOR.png or .pgm with --resolution; or a ROS map_server / nav2 map's "
      "YAML, which names its image, resolution, origin and thresholds) becomes a one-level plan: "
      "dark regions are traced into straight walls (any angle, with their thickness) and columns, "
      "a gap in a line of wall where a person fits through (0.6-2.5 m) is a doorway, and the free "
      "regions the walls enclose are rooms; what is not straight walls (curves, hatching, text) is "
      "said, one line each. The image's bottom-left corner is the plan's origin unless --origin "
      "(or the YAML) says otherwise. The rules and their thresholds: docs/formats.md, \"Importing "
      "raster floor plans\".\n\n"
      "Example:\n  isg import floor2.png --resolution 0.01 -o floor2.json\n"
      "  isg import map.yaml -o lab.json --height 2.8\n\n"
      "Example:\n  isg import walk.bag -o datasets/walk\n  isg import rosbag2_walk/ -o "
      "datasets/walk2\n"
      "  isg import walk.bag -o datasets/walk --lidar-topic /os_cloud_node/points --start 20 "
      "--duration 60\n  isg slam datasets/walk --plan lab.json -o runs/walk");
  app_->add_option("model", input_,
                   "IFC file (STEP, .ifc), floor plan image (.png, .pgm), ROS map (.yaml) or a "
                   "recording (.bag, .db3, .mcap, a rosbag2 folder) to read")
      ->option_text("MODEL.ifc|FLOOR.png|MAP.yaml|RECORDING.bag|.db3|.mcap|BAG_DIR")
      ->required();
  app_->add_option("-o,--output", output_,
                   "plan file (from IFC or a floor plan) or dataset folder (from a recording)")
      ->option_text("PLAN.json|DATASET_DIR")
      ->required();
  addRasterOptions();
  addRecordingOptions();
  app_->add_option("--storey", storeys_,
                   "import this storey (its IFC name; repeat for several) instead of choosing")
      ->option_text("NAME");
  app_->add_flag("--force", force_, "replace the output if isg wrote it before");
  app_->add_flag("-q,--quiet", quiet_,
                 "print only the summary (no element left out of an IFC model, no progress bar)");
}

// Raster floor plans: the image's scale, origin and the walls' height.
void ImportCommand::addRasterOptions() {
  auto* raster = "Raster floor plans (.png, .pgm, .yaml)";
  app_->add_option("--resolution", resolution_,
                   "metres a pixel of a floor plan image (a map's YAML gives its own)")
      ->check(numberIn(1e-4, 10.0))
      ->option_text("M")
      ->group(raster);
  app_->add_option("--origin", origin_,
                   "where the image's bottom-left corner lies in the plan, x,y in metres (default "
                   "0,0; a map's YAML gives its own)")
      ->delimiter(',')
      ->expected(2)
      ->check(numberIn(-bim::limits::kMaxCoordinate, bim::limits::kMaxCoordinate))
      ->option_text("X,Y")
      ->group(raster);
  app_->add_option("--height", wall_height_, "the walls' height, floor to ceiling, m")
      ->check(numberIn(0.1, 100.0))
      ->capture_default_str()
      ->option_text("H")
      ->group(raster);
}

// Recordings: which topics and frames, which stretch of time, the sensors' mounts.
void ImportCommand::addRecordingOptions() {
  auto* bag = "Recordings (.bag)";
  app_->add_option("--lidar-topic", lidar_topic_, "the point clouds' topic")
      ->option_text("TOPIC")
      ->group(bag);
  app_->add_option("--imu-topic", imu_topic_, "the IMU's topic (none: leave the IMU out)")
      ->option_text("TOPIC")
      ->group(bag);
  app_->add_option("--odom-topic", odometry_topic_,
                   "the odometry's topic: nav_msgs/Odometry, or a tf topic (/tf) whose transforms "
                   "join the odometry's frame to the base (none: leave it out)")
      ->option_text("TOPIC")
      ->group(bag);
  app_->add_option("--odom-frame", odometry_frame_,
                   "odometry from /tf: its fixed frame (default: the frame above the LiDAR named "
                   "odom…)")
      ->option_text("FRAME")
      ->group(bag);
  app_->add_option("--ground-truth-topic", ground_truth_topic_,
                   "the ground truth's topic, nav_msgs/Odometry or geometry_msgs/PoseStamped "
                   "(none: leave it out)")
      ->option_text("TOPIC")
      ->group(bag);
  app_->add_option("--start", start_,
                   "import from this many seconds after the recording's first message")
      ->check(numberIn(0.0, 1e7))
      ->option_text("S")
      ->group(bag);
  app_->add_option("--duration", duration_, "import this many seconds (default: to the end)")
      ->check(numberIn(0.001, 1e7))
      ->option_text("S")
      ->group(bag);
  app_->add_option("--base-frame", base_frame_,
                   "the robot's base frame (default: the odometry's child frame, or on /tf "
                   "base_link or the frame the odometry moves; without odometry, the ground "
                   "truth's child frame when /tf_static joins it to the LiDAR, else the LiDAR's "
                   "frame)")
      ->option_text("FRAME")
      ->group(bag);
  app_->add_option("--lidar-extrinsic", lidar_extrinsic_,
                   "the LiDAR's pose on the base when /tf_static lacks it: x,y,z (m), roll, "
                   "pitch, yaw (rad)")
      ->delimiter(',')
      ->expected(6)
      ->option_text("X,Y,Z,R,P,Y")
      ->group(bag);
  app_->add_option("--imu-extrinsic", imu_extrinsic_,
                   "the IMU's pose on the base when /tf_static lacks it: x,y,z (m), roll, pitch, "
                   "yaw (rad)")
      ->delimiter(',')
      ->expected(6)
      ->option_text("X,Y,Z,R,P,Y")
      ->group(bag);
}

namespace {

// Images of kinds the raster import does not read: said as such, not handed to the IFC reader.
void refuseOtherImages(const std::string& path) {
  const std::string extension = lowerExtension(path);
  for (const char* other : {".jpg", ".jpeg", ".bmp", ".tif", ".tiff", ".gif", ".webp"}) {
    if (extension == other) {
      throw common::InputError(path, "",
                               "a " + extension.substr(1) +
                                   " image: floor plan images are read as PNG or PGM (convert "
                                   "it losslessly, e.g. `convert FLOOR" +
                                   extension + " FLOOR.png`)");
    }
  }
}

}  // namespace

int ImportCommand::run() {
  refuseOtherImages(input_);
  if (isRecording(input_)) return importBag();
  if (isRasterImage(input_) || isMapYaml(input_)) return importRaster();
  return importIfc();
}

int ImportCommand::importRaster() {
  const bool yaml = isMapYaml(input_);
  if (yaml && (resolution_ > 0.0 || !origin_.empty())) {
    throw common::InputError(input_, "",
                             "a map's YAML gives its own resolution and origin: leave out "
                             "--resolution and --origin (or edit the YAML)");
  }
  if (!yaml && !(resolution_ > 0.0)) {
    throw common::InputError(input_, "",
                             "a floor plan image needs its scale: --resolution M (metres a "
                             "pixel; 0.01 for a plan drawn at 1 cm a pixel)");
  }
  common::checkOutputPath(output_, {common::OutputKind::kImportedPlan, {input_}, force_, true});
  raster::RasterPlanOptions options;
  options.height = wall_height_;
  std::string image = input_;
  // A plain image: a pixel darker than mid-grey is occupied, else free.
  formats::OccupancyRule rule{formats::OccupancyRule::Mode::kTrinary, false, 0.5, 0.5};
  if (yaml) {
    const formats::MapYaml map = formats::readMapYaml(input_);
    image = map.image;
    options.resolution = map.resolution;
    options.origin = Eigen::Vector2d(map.origin_x, map.origin_y);
    options.yaw = map.origin_yaw;
    rule = map.rule;
    options.source_kind = "ROS map";
    options.from_file = input_;
  } else {
    options.resolution = resolution_;
    if (!origin_.empty()) options.origin = Eigen::Vector2d(origin_[0], origin_[1]);
    options.source_kind = lowerExtension(input_) == ".png" ? "PNG image" : "PGM image";
  }
  options.check_interrupt = run::throwIfInterrupted;
  // The image's size is held to a level's extent on its header, before any pixel is decoded.
  const auto check_size = [&](long long width, long long height) {
    raster::checkImageExtent(width, height, image, options);
  };
  const raster::RasterPlanImport result = raster::rasterPlanFromImage(
      formats::readOccupancyImage(image, rule, check_size), image, options);
  nlohmann::ordered_json document = result.plan_json;
  roundNumbers(document);
  run::throwIfInterrupted();
  writeFileAtomically(output_, document.dump(2) + "\n");
  if (!quiet_) {
    for (const auto& line : result.log) std::fprintf(stderr, "  %s\n", line.c_str());
  }
  std::fprintf(stderr, "isg import: %s: %d × %d pixels at %g m a pixel (%.1f m × %.1f m)\n",
               image.c_str(), result.width, result.height, options.resolution,
               result.width * options.resolution, result.height * options.resolution);
  std::fprintf(stderr,
               "isg import: wrote %s: 1 level, %s, %s, %s%s, %s; %s left out or "
               "simplified%s\n",
               output_.c_str(), common::counted(result.walls, "wall").c_str(),
               common::counted(result.columns, "column").c_str(),
               common::counted(result.doors, "doorway").c_str(),
               result.doorway_gaps > 0 ? (" (and " + std::to_string(result.doorway_gaps) +
                                          " between no rooms, written as gaps in their walls)")
                                             .c_str()
                                       : "",
               common::counted(result.rooms, "room").c_str(),
               common::counted(result.log.size(), "region").c_str(),
               quiet_ && !result.log.empty() ? " (run without -q to list them)" : "");
  return kExitOk;
}

int ImportCommand::importBag() {
  common::checkCanCreateFolder(output_, common::OutputKind::kDataset, force_, {input_});
  recordings::BagImportOptions options;
  options.lidar_topic = lidar_topic_;
  options.imu_topic = imu_topic_;
  options.odometry_topic = odometry_topic_;
  options.odometry_frame = odometry_frame_;
  options.ground_truth_topic = ground_truth_topic_;
  options.start = start_;
  if (duration_ > 0) options.duration = duration_;
  options.base_frame = base_frame_;
  options.lidar_extrinsic = mountOption(lidar_extrinsic_);
  options.imu_extrinsic = mountOption(imu_extrinsic_);
  options.overwrite = force_;
  ProgressBar bar("isg import", quiet_);
  const auto summary = recordings::importRosbag(
      input_, output_, options, [&](std::uint64_t done, std::uint64_t total) {
        run::throwIfInterrupted();
        char detail[64];
        std::snprintf(detail, sizeof detail, "%llu/%llu clouds", (unsigned long long)done,
                      (unsigned long long)total);
        bar.update(total > 0 ? double(done) / double(total) : 1.0, detail);
      });
  bar.finish();
  const auto stream = [](const char* what, const recordings::BagImportSummary::Stream& s) {
    if (s.topic.empty()) {
      std::printf("  %-13s none\n", what);
    } else {
      std::printf("  %-13s %s (%s): %s\n", what, s.topic.c_str(), s.type.c_str(),
                  common::counted(s.messages, "message").c_str());
    }
  };
  std::printf("isg import: %s -> %s%s\n", input_.c_str(), output_.c_str(),
              summary.from_isg ? " (a bag of an isg dataset: its metadata restored)" : "");
  stream("LiDAR", summary.lidar);
  stream("IMU", summary.imu);
  stream("odometry", summary.odometry);
  stream("ground truth", summary.ground_truth);
  std::printf(
      "  clouds: %s; stamped at the %s (point times %.4f to %.4f s about the stamp); %.4f s "
      "apart; %.1f points each on average\n",
      summary.cloud_layout.c_str(), summary.stamp == "last_packet" ? "end of the turn" : "start",
      summary.point_time[0], summary.point_time[1], summary.scan_period,
      summary.lidar.messages > 0 ? double(summary.points) / double(summary.lidar.messages) : 0.0);
  for (const auto& note : summary.notes) std::printf("  note: %s\n", note.c_str());
  std::printf("isg import: wrote %s: %s, %.1f s of robot time%s\n", output_.c_str(),
              common::counted(summary.lidar.messages, "scan").c_str(), summary.seconds,
              summary.odometry.topic.empty()
                  ? "; no odometry: isg slam makes it from the LiDAR (and the IMU)"
                  : "");
  return kExitOk;
}

int ImportCommand::importIfc() {
  common::checkOutputPath(output_, {common::OutputKind::kImportedPlan, {input_}, force_, true});
  ifc::ImportOptions options;
  options.storeys = storeys_;
  ifc::ImportResult result;
  try {
    result = ifc::importIfc(input_, options);
  } catch (const ifc::ImportInterrupted& e) {
    std::fprintf(stderr, "isg import: %s; nothing was written\n", e.what());
    return 128 + e.signalNumber();
  }
  roundNumbers(result.plan_json);
  run::throwIfInterrupted();  // a Ctrl-C that reached isg after the model was read
  writeFileAtomically(output_, result.plan_json.dump(2) + "\n");

  if (!quiet_) {
    for (const auto& line : result.log) std::fprintf(stderr, "  %s\n", line.c_str());
    for (const auto& warning : result.warnings)
      std::fprintf(stderr, "  warning: %s\n", warning.str().c_str());
  }
  std::fprintf(
      stderr, "isg import: %s: %s%s%s, lengths in %s\n", input_.c_str(), result.schema.c_str(),
      result.application.empty() ? "" : " from ", result.application.c_str(),
      result.metres_per_unit == 1.0 ? "metres"
                                    : (std::to_string(result.metres_per_unit) + " m").c_str());
  int walls = 0, doors = 0, windows = 0, rooms = 0, levels = 0, columns = 0;
  for (const auto& s : result.storeys) {
    if (s.level_id.empty()) {
      std::fprintf(stderr, "  storey \"%s\" (%.3f m): not imported: %s\n", s.name.c_str(),
                   s.elevation, s.why_not.c_str());
      continue;
    }
    ++levels;
    walls += s.walls, doors += s.doors, windows += s.windows, rooms += s.rooms;
    columns += s.columns;
    const std::string column_count =
        s.columns > 0 ? ", " + common::counted(s.columns, "column") : "";
    std::fprintf(
        stderr,
        "  storey \"%s\" (%.3f m) -> level %s: %s (%d of another storey standing on "
        "it)%s, %s, %s, %s of %s\n",
        s.name.c_str(), s.elevation, s.level_id.c_str(), common::counted(s.walls, "wall").c_str(),
        s.walls_from_other_storeys, column_count.c_str(), common::counted(s.doors, "door").c_str(),
        common::counted(s.windows, "window").c_str(), common::counted(s.rooms, "room").c_str(),
        common::counted(s.spaces, "space").c_str());
  }
  const std::string column_total = columns > 0 ? ", " + common::counted(columns, "column") : "";
  std::fprintf(stderr, "isg import: wrote %s: %s, %s%s, %s, %s, %s; %s left out or simplified%s\n",
               output_.c_str(), common::counted(levels, "level").c_str(),
               common::counted(walls, "wall").c_str(), column_total.c_str(),
               common::counted(doors, "door").c_str(), common::counted(windows, "window").c_str(),
               common::counted(rooms, "room").c_str(),
               common::counted(result.log.size(), "element").c_str(),
               quiet_ && !result.log.empty() ? " (run without -q to list them)" : "");
  if (!result.reader_errors.empty()) {
    std::fprintf(stderr, "isg import: IFC++ reported %zu error%s while reading (first: %s)\n",
                 result.reader_errors.size(), result.reader_errors.size() == 1 ? "" : "s",
                 result.reader_errors.front().c_str());
  }
  return kExitOk;
}

}  // namespace isg::cli
