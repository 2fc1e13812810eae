#pragma once

#include <optional>
#include <string>

#include "bim/plan.hpp"
#include "run/room_evaluation.hpp"
#include "sensors/sensor_streams.hpp"
#include "slam/map_diagnostics.hpp"
#include "slam/timing_report.hpp"

namespace isg::run {

// What `isg slam` reports of a method's map beside the run's metrics: its size, its keyframes
// against ground truth after SE(3) alignment (and odometry at the same instants, to compare),
// the rooms it found in the plan, and the per-keyframe timings as the graph grew.
struct MapDiagnosis {
  std::size_t keyframes = 0, planes = 0, rooms = 0;
  std::optional<double> keyframe_ape_rmse;  // SE(3)-aligned; with ground truth, >= 3 keyframes
  std::optional<double> odometry_ape_rmse;  // odometry at the keyframes' stamps, likewise
  std::optional<RoomDetectionReport> room_detection;  // with a plan as well
  std::vector<slam::TimingAt> timing;                 // around 50, 200 and 500 keyframes
  std::optional<std::string> note;                    // why a measure is missing
};

MapDiagnosis diagnoseMap(const slam::MapDiagnostics& map, common::PoseSequence ground_truth,
                         const bim::Plan* plan, const std::string& level);

// The lines `isg slam` prints.
std::string formatMapDiagnosis(const MapDiagnosis& diagnosis);

}  // namespace isg::run
