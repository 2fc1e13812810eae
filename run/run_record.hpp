#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "bim/agraph.hpp"
#include "bim/plan.hpp"
#include "bim/scenario.hpp"
#include "run/estimate_states.hpp"
#include "sensors/sensor_streams.hpp"
#include "sensors/stage_times.hpp"
#include "slam/map_diagnostics.hpp"

namespace isg::run {

// A run's trajectories are the sensor streams' type (TUM rows).
using common::StampedPose;
using common::Trajectory;

// What a run is: the world, the method and the seed, and the plan it is measured in.
struct RunSetup {
  std::string world;   // what the user named: a file, builtin:NAME, or the dataset folder
  std::string method;  // the localizer's name
  std::uint64_t seed = 0;
  std::string world_hash;           // worlds::worldHash of the world; empty when there is none
  const bim::Plan* plan = nullptr;  // for agraph.json and the report; may be null
  const bim::AGraph* agraph = nullptr;
  std::string level;
  const bim::AsBuilt* as_built = nullptr;  // what the simulated building changed; may be null
  // The method's options with the values it ran with, given or default
  // (LocalizerRegistry::checkOptions); empty for a method without options.
  std::map<std::string, double> method_options;
  // The simulated LiDAR's model (bim::LidarConfig::model); empty for a replayed dataset.
  std::string lidar_model;
};

// A thinned copy of a scan the localizer read, kept for the map-to-plan error
// (docs/evaluation.md): its stamp and every kMapSampleStride-th point in L, with its time from
// the stamp. One scan per kMapSampleSeconds of robot time (a few megabytes a minute), at most
// kMaxMapSamples of them: a longer run keeps every other one and doubles the spacing
// (run/map_samples.hpp), so that hours of robot time keep the map sample's memory bounded.
// 256 scans of ~3500 points are ~0.9 M points (~14 MB, and as much again while the evaluation
// measures them): the error's statistics are then as steady as with more, the scans still
// spread over the whole run, and a walk of ten minutes (a scan every 2–3 s once the localizer
// reads only keyframes) already holds as many as one of hours, so memory stops growing here.
struct MapScanSample {
  double stamp = 0.0;
  std::vector<std::array<float, 4>> points;  // x y z time
};
inline constexpr int kMapSampleStride = 8;
inline constexpr double kMapSampleSeconds = 1.0;
inline constexpr std::size_t kMaxMapSamples = 256;

// What one run produced, from the live loop (`isg run`) or a replay (`isg slam`): the streams it
// was fed, what the localizer said after each scan, and what it can tell about itself.
struct RunRecord {
  RunSetup setup;
  // All but the IMU's samples: nothing after the loop reads them, so the loop lets them go once
  // fed (two hours at 200 Hz are 81 MB).
  sensors::SensorStreams streams;
  Trajectory estimate_map;                     // M, after each scan
  Trajectory estimate;                         // B, from the first localized pose on, one per scan
  std::vector<EstimateState> estimate_states;  // one per pose of `estimate`
  std::optional<double> localized_at;          // stamp of the first pose in B
  int scans = 0;
  int scans_read = 0;  // by the localizer; the others were skipped (never made or read)
  double wall_seconds = 0.0;
  // Where the time went: seconds by stage, the scan source's (poses, casting, noise on every
  // thread; or reading) then the localizer's (deskew, extraction, ..., matching, and "localizer,
  // other" for the rest of its calls); and the loop's wall time in the localizer's calls and
  // waiting for scans (on one thread, making them).
  sensors::StageTimes stage_times;
  double localizer_seconds = 0.0;
  double scan_wait_seconds = 0.0;
  nlohmann::json graph;  // the localizer's final graph (sgraph.json)
  std::optional<std::string> search_status;
  std::vector<slam::StatusChange> status_changes;
  std::optional<slam::MapDiagnostics> map;
  std::vector<MapScanSample> map_samples;
  double map_sample_seconds = kMapSampleSeconds;  // the samples' spacing now (doubles when full)
  // Where the map lies in the plan at the end, as the plan last confirmed it
  // (LocalizerDriver::confirmedMapInPlan): none when the run ended lost.
  std::optional<Eigen::Isometry3d> final_B_T_M;
};

}  // namespace isg::run
