#include "cli/recording_frame.hpp"

#include <filesystem>

#include "sensors/mount_transform.hpp"

namespace isg::cli {

std::optional<RecordingFrame> recordingFrameOf(const bim::Scenario& scenario) {
  const bim::Route& route = scenario.robot.route;
  if (route.kind != bim::Route::Kind::kTrajectory) return std::nullopt;
  RecordingFrame frame;
  frame.sequence = std::filesystem::path(route.trajectory_file).stem().string();
  frame.clock_start = route.recording_start;
  frame.body_path = !route.sensor_path;
  if (route.sensor_path) {
    frame.R_T_S = sensors::mountTransform(scenario.lidar.mount) *
                  sensors::mountTransform(route.rig).inverse();
  }
  return frame;
}

}  // namespace isg::cli
