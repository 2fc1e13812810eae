#include "sim/dataset_writer.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

#include "bim/plan_json.hpp"
#include "common/atomic_folder.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "common/version.hpp"
#include "formats/dataset_format.hpp"
#include "formats/dataset_metadata.hpp"
#include "sim/vlp16.hpp"

namespace isg::sim {

namespace fs = std::filesystem;
using common::writeFile;
using common::writeFolderAtomically;

namespace {

// The simulated sensors' models and conventions, beyond what every dataset's LiDAR section says
// (formats::dataset::Metadata): what a user needs to reproduce or compare the scans.
nlohmann::ordered_json lidarModel(const Simulation& sim) {
  const auto& l = sim.scenario().lidar;
  const LidarSimulator& lidar = sim.lidar();
  const sensors::LidarModel& model = lidar.model();
  std::vector<double> elevation, vertical_offset, firing_offset, azimuth_offset;
  double lowest = 90.0;
  for (const auto& beam : model.beams) {
    elevation.push_back(beam.elevation_deg);
    vertical_offset.push_back(beam.vertical_offset_mm);
    firing_offset.push_back(beam.firing_offset_s);
    azimuth_offset.push_back(beam.azimuth_offset_deg);
    lowest = std::min(lowest, beam.elevation_deg);
  }
  // lidar.model is the dataset format's (the title, "Velodyne VLP-16"); the scenario's name too.
  nlohmann::ordered_json out = {{"scenario_model", model.name},
                                {"sequences_per_turn", model.sequencesPerTurn(l.rate_hz)},
                                {"sequences_per_cloud", lidar.sequencesPerCloud()},
                                {"cut", bim::lidarCutName(l.cut)},
                                {"cut_angle_deg", l.cut_angle_deg},
                                {"azimuth_jitter_deg", l.azimuth_jitter_deg},
                                {"returns", bim::lidarReturnsName(l.returns)}};
  // The VLP-16 fires its lasers at a fixed interval; the others' offsets are listed per laser.
  if (model.name == "vlp16") {
    out["firing_interval_s"] = Vlp16::kFiringInterval;
  } else {
    out["firing_offset_s_by_laser"] = firing_offset;
    out["azimuth_offset_deg_by_laser"] = azimuth_offset;
    out["beam_origin_radius_mm"] = model.beam_origin_radius_mm;
  }
  out["sequence_duration_s"] = model.sequenceDuration(l.rate_hz);
  out["elevation_deg_by_laser"] = elevation;
  out["vertical_offset_mm_by_laser"] = vertical_offset;
  out["ring"] = "laser index by elevation: ring 0 = " + common::formatNumber(lowest) + " deg";
  const nlohmann::ordered_json rest = {
      {"rotation", "clockwise seen from above"},
      {"range_noise_m", l.range_noise_m},
      {"range_quantum_m", model.range_resolution_m},
      {"min_range_m", l.min_range_m},
      {"max_range_m", l.max_range_m},
      {"dropout", l.dropout},
      {"grazing_cutoff_deg", l.grazing_cutoff_deg},
      {"detection_range_m", l.detection_range_m},
      {"body_occlusion", l.body_occlusion},
      {"reflectivity",
       {{"wall", l.reflectivity.wall},
        {"floor", l.reflectivity.floor},
        {"ceiling", l.reflectivity.ceiling},
        {"door", l.reflectivity.door},
        {"clutter", l.reflectivity.clutter},
        {"stair", l.reflectivity.stair}}},
      {"intensity",
       "calibrated reflectivity: round(100 * reflectivity * |cos(incidence)|), the surface's "
       "reflectivity by kind"},
      {"lost_returns",
       "rays that meet the robot's body (body_occlusion); returns weaker than a 10 % surface "
       "head-on at detection_range_m (reflectivity * cos(incidence) / range^2); beyond "
       "grazing_cutoff_deg kept with probability cos(incidence) / cos(cutoff); dropout"},
      {"pcd_fields",
       "x y z intensity ring time (float32 ×4, uint16, float32), time from the scan stamp "
       "(within point_time_s)"}};
  for (const auto& [key, value] : rest.items()) out[key] = value;
  return out;
}

// The robot: carrier, gait, route, rooms and kidnaps (where each put the robot down, the planned
// pose in B, and on which level when the plan has several).
// What a replayed walk went through (worlds::takeCrossedSolids): its mode, and each pass with the
// element, what it was taken as, where and on which lines of the walk's file.
nlohmann::ordered_json crossingsJson(const bim::Route& route) {
  static constexpr const char* kModes[] = {"not_built", "opening", "refuse"};
  nlohmann::ordered_json passes = nlohmann::ordered_json::array();
  for (const auto& c : route.crossings) {
    passes.push_back({{"element", c.element},
                      {"kind", c.column ? "column" : "wall"},
                      {"taken_as", c.opening ? "opening" : "not_built"},
                      {"at", {c.at.x(), c.at.y()}},
                      {"lines", {c.first_line, c.last_line}}});
  }
  return {{"mode", kModes[int(route.crossed)]}, {"passes", std::move(passes)}};
}

nlohmann::ordered_json robotDescription(const Simulation& sim) {
  using json = nlohmann::ordered_json;
  const bim::Scenario& s = sim.scenario();
  json kidnaps = json::array();
  for (const auto& leg : sim.route().kidnaps) {
    json kidnap = {{"time", leg.time},
                   {"to", {leg.waypoints.front().x(), leg.waypoints.front().y(), leg.start_yaw}}};
    if (s.plan.levels.size() > 1) kidnap["level"] = leg.waypoint_levels.front();
    kidnaps.push_back(std::move(kidnap));
  }
  json route = json::array();
  for (const auto& p : sim.route().waypoints) route.push_back({p.x(), p.y()});
  const auto& gait = sim.baseMotion().gait();
  json robot = {{"carrier", bim::carrierName(s.robot.carrier)},
                {"level", s.robot.level},
                {"speed", s.robot.speed},
                {"turn_rate_rad_s", gait.turn_rate},
                {"standing_height_m", gait.standing_height},
                {"gait",
                 {{"frequency_hz", gait.frequency_hz},
                  {"bob_m", gait.bob_m},
                  {"roll_deg", gait.roll_deg},
                  {"pitch_deg", gait.pitch_deg}}},
                {"route", route},
                {"visited_rooms", sim.route().visited_rooms},
                {"skipped_rooms", sim.route().skipped_rooms},
                {"kidnaps", kidnaps}};
  if (s.robot.carrier == bim::Carrier::kHandheld) {
    // A person's walk: the walker's sway and head turns.
    robot["gait"]["sway_m"] = gait.sway_m;
    robot["gait"]["head_turn_deg"] = gait.head_turn_deg;
    robot["gait"]["head_turn_periods_s"] = kHeadTurnPeriods;
  }
  if (const WalkPath* walk = sim.baseMotion().walk()) {
    // A replayed walk: its file, how it was faced, and how closely the path follows the file; its
    // speed is the mean pace along its route (the file's positions 0.1 m apart, so that their
    // jitter does not add length).
    const auto& points = sim.route().waypoints;
    double length = 0.0;
    for (std::size_t i = 1; i < points.size(); ++i) length += (points[i] - points[i - 1]).norm();
    robot["speed"] = length / std::max(walk->duration(), 1e-9);
    robot["trajectory"] = {{"file", s.robot.route.trajectory_file},
                           {"poses", s.robot.route.walk.size()},
                           {"orientation", s.robot.route.file_orientation ? "file" : "travel"},
                           {"knot_spacing_s", kWalkKnotSpacing},
                           {"deviation_median_m", walk->medianDeviation()},
                           {"deviation_max_m", walk->maxDeviation()},
                           {"deviation_max_line", walk->maxDeviationLine()}};
    robot["trajectory"]["path_of"] = s.robot.route.sensor_path ? "sensor" : "body";
    if (s.robot.route.sensor_path) robot["trajectory"]["rig"] = s.robot.route.rig;
    robot["trajectory"]["crossed"] = crossingsJson(s.robot.route);
  }
  // Which level each waypoint is on, written only when the route changes level (a route on one
  // level writes the metadata it always did); the levels the tour skipped whenever there are any.
  const auto& levels = sim.route().waypoint_levels;
  if (std::any_of(levels.begin(), levels.end(),
                  [&](const std::string& level) { return level != levels.front(); })) {
    robot["route_levels"] = levels;
    robot["skipped_levels"] = sim.route().skipped_levels;
  } else if (!sim.route().skipped_levels.empty()) {
    robot["skipped_levels"] = sim.route().skipped_levels;
  }
  return robot;
}

nlohmann::ordered_json metadata(const Simulation& sim, double duration,
                                const DatasetOptions& options, int scans, int imu_samples) {
  const bim::Scenario& s = sim.scenario();
  const auto& l = s.lidar;
  const LidarSimulator& lidar = sim.lidar();
  const auto& imu = s.imu;
  formats::dataset::Metadata m;
  m.generator = std::string("isg simulate ") + common::kProjectVersion;
  m.duration_s = duration;
  m.frames = {
      {"B", "plan frame (ground truth, scans.tum)"},
      {"M", "odometry frame: the start pose of the base (odometry.tum)"},
      {"R", "robot base, x forward, y left, z up (groundtruth.tum is B_T_R)"},
      {"L", "LiDAR: the frame of every point of scans/*.pcd, at the point's own firing time"},
      {"I", "IMU: the frame of imu.csv's readings"}};
  m.lidar_mount = l.mount;
  m.R_T_L = sim.R_T_L();
  m.imu_mount = {imu.mount, sim.R_T_I()};
  m.lidar = {
      lidar.model().title, l.rate_hz,
      std::size_t(scans),  bim::lidarStampName(l.stamp),
      lidar.scanPeriod(),  {-lidar.stampOffset(), lidar.turnDuration() - lidar.stampOffset()},
      options.pcd};
  m.imu =
      formats::dataset::Metadata::Imu{imu.rate_hz, std::size_t(imu_samples),
                                      imu.gyroscope_noise_density, imu.accelerometer_noise_density};
  // A handheld carrier has no odometry stream (odometry.tum is not written).
  if (s.robot.carrier != bim::Carrier::kHandheld) m.odometry = {s.odometry.rate_hz};
  nlohmann::ordered_json description = {
      {"scenario", s.source},
      {"plan_file", s.plan_file},
      {"seed", s.seed},
      {"lidar", lidarModel(sim)},
      {"imu",
       {{"columns",
         "t,ax,ay,az,gx,gy,gz: seconds, specific force in m/s² (gravity included: "
         "+g upwards at rest), angular velocity in rad/s, all in I"},
        {"gravity_m_s2", imu.gravity},
        {"gyroscope_random_walk", imu.gyroscope_random_walk},
        {"accelerometer_random_walk", imu.accelerometer_random_walk},
        {"noise_units",
         "densities in rad/s/√Hz and m/s²/√Hz, random walks in rad/s²/√Hz and "
         "m/s³/√Hz (Kalibr's imu.yaml); biases start at zero"},
        {"kidnaps", "not felt: the lift has no modelled motion"}}},
      {"groundtruth_rate_hz", options.groundtruth_rate},
      {"robot", robotDescription(sim)},
      {"plan", bim::planToJson(s.plan)},
      {"as_built", bim::asBuiltToJson(s.as_built)}};
  if (m.odometry) {
    description["odometry"] = {
        {"translation_noise", s.odometry.translation_noise},
        {"heading_noise_deg_per_m", s.odometry.heading_noise_deg_per_m},
        {"heading_bias_deg_per_m", s.odometry.heading_bias_deg_per_m},
        {"model", "random walk: std over 1 m = translation_noise m and heading_noise deg"}};
  }
  return formats::dataset::metadataJson(m, description);
}

}  // namespace

DatasetSummary writeDataset(Simulation& sim, const std::string& dir, const DatasetOptions& options,
                            const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  DatasetSummary summary;
  writeFolderAtomically(
      dir, common::OutputKind::kDataset, options.overwrite, [&](const fs::path& temporary) {
        fs::create_directories(temporary / formats::dataset::kScans);
        const double duration =
            options.duration < 0 ? sim.duration() : std::min(options.duration, sim.duration());
        summary.sim_seconds = duration;
        const int scans = sim.scanCount(duration);
        summary.scans = scans;
        std::atomic<int> next{0}, done{0};
        std::atomic<std::size_t> points{0}, rays{0}, scan_bytes{0};
        std::mutex report;
        std::exception_ptr error;  // the first worker's error, rethrown here after the join
        auto worker = [&] {
          try {
            const auto lidar = sim.makeLidar();
            for (int k = next++; k < scans; k = next++) {
              const LidarScan scan = sim.scan(k, *lidar);
              const std::string bytes = formats::dataset::pcdBytes(scan.points, options.pcd);
              writeFile(temporary / formats::dataset::kScans / formats::dataset::scanFileName(k),
                        bytes);
              scan_bytes += bytes.size();
              points += scan.points.size();
              rays += std::size_t(scan.rays);
              const int finished = ++done;
              if (progress) {
                std::lock_guard<std::mutex> lock(report);
                progress(finished, scans);
              }
            }
          } catch (...) {
            std::lock_guard<std::mutex> lock(report);
            if (!error) error = std::current_exception();
            next = scans;  // the others stop after their current scan
          }
        };
        std::vector<std::thread> pool;
        for (int i = 1; i < std::max(1, options.threads); ++i) pool.emplace_back(worker);
        worker();
        for (auto& t : pool) t.join();
        if (error) std::rethrow_exception(error);
        summary.points = points;
        summary.rays = rays;
        summary.scan_bytes = scan_bytes;

        using namespace formats::dataset;
        writeFile(temporary / kGroundTruth,
                  trajectoryText(sim.groundTruth(duration, options.groundtruth_rate)));
        if (const auto odometry = sim.odometry(duration); !odometry.empty()) {
          writeFile(temporary / kOdometry, trajectoryText(odometry));
        }
        writeFile(temporary / kScanPoses, trajectoryText(sim.scanPoses(duration)));
        const std::vector<ImuSample> imu = sim.imu(duration);
        writeFile(temporary / kImu, imuText(imu));
        writeFile(temporary / kMetadata,
                  metadata(sim, duration, options, scans, int(imu.size())).dump(2) + "\n");
        summary.wall_seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (options.also_write) options.also_write(temporary);
      });
  return summary;
}

}  // namespace isg::sim
