#include "run/map_diagnosis.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "eval/ape.hpp"

namespace isg::run {

MapDiagnosis diagnoseMap(const slam::MapDiagnostics& map, common::PoseSequence ground_truth,
                         const bim::Plan* plan, const std::string& level) {
  MapDiagnosis out;
  out.keyframes = map.keyframes.size();
  out.planes = map.planes;
  out.rooms = map.rooms.size();
  out.timing = slam::timingAt(map.timings, {50, 200, 500});
  if (ground_truth.empty() || map.keyframes.size() < 3) return out;
  common::Trajectory keyframes, odometry;
  for (const auto& kf : map.keyframes) {
    keyframes.push_back({kf.stamp, kf.estimate});
    odometry.push_back({kf.stamp, kf.odometry});
  }
  eval::ErrorOptions se3;
  se3.align = eval::Alignment::kSE3;
  eval::ErrorResult keyframe_ape;
  try {
    keyframe_ape = eval::absolutePoseError(ground_truth, keyframes, se3);
    out.keyframe_ape_rmse = keyframe_ape.translation_stats.rmse;
    out.odometry_ape_rmse =
        eval::absolutePoseError(ground_truth, odometry, se3).translation_stats.rmse;
  } catch (const std::invalid_argument& e) {
    // Keyframes on a straight line (a short run) cannot be aligned: say so, measure nothing.
    out.keyframe_ape_rmse.reset();
    out.odometry_ape_rmse.reset();
    out.note = std::string("keyframe APE not computed: ") + e.what();
    return out;
  }
  if (plan != nullptr && keyframe_ape.alignment) {
    out.room_detection =
        evaluateRooms(*plan, level, map.rooms, ground_truth, *keyframe_ape.alignment);
  }
  return out;
}

std::string formatMapDiagnosis(const MapDiagnosis& d) {
  char line[512];
  std::string out;
  std::snprintf(line, sizeof line, "  map: %zu keyframe%s, %zu wall plane%s, %zu room%s\n",
                d.keyframes, d.keyframes == 1 ? "" : "s", d.planes, d.planes == 1 ? "" : "s",
                d.rooms, d.rooms == 1 ? "" : "s");
  out += line;
  out += slam::formatTiming(d.timing);
  if (d.keyframe_ape_rmse && d.odometry_ape_rmse) {
    std::snprintf(line, sizeof line,
                  "  keyframes after SE(3) alignment: APE rmse %.3f m (odometry at the same "
                  "instants %.3f m, %.1fx)\n",
                  *d.keyframe_ape_rmse, *d.odometry_ape_rmse,
                  *d.odometry_ape_rmse / std::max(*d.keyframe_ape_rmse, 1e-12));
    out += line;
  }
  if (d.note) out += "  note: " + *d.note + "\n";
  if (const auto& r = d.room_detection) {
    std::string missed;
    for (const auto& id : r->walked) {
      if (std::find(r->detected.begin(), r->detected.end(), id) == r->detected.end()) {
        missed += (missed.empty() ? "" : ", ") + id;
      }
    }
    std::snprintf(
        line, sizeof line,
        "  rooms: %zu detected of %zu walked through (%.0f %%), widths within %.3f m%s%s\n",
        r->detected.size(), r->walked.size(), 100.0 * r->rate(), r->worst_width_error,
        missed.empty() ? "" : "; missed: ", missed.c_str());
    out += line;
  }
  return out;
}

}  // namespace isg::run
