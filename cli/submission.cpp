#include "cli/submission.hpp"

#include <algorithm>

#include "cli/recording_frame.hpp"
#include "common/atomic_folder.hpp"
#include "common/output_path.hpp"
#include "common/tum.hpp"
#include "eval/floor_plan_score.hpp"
#include "worlds/reference_plans.hpp"

namespace isg::cli {

SubmissionTarget planSubmission(const std::string& dir, const bim::Scenario& scenario,
                                const std::string& input, bool force,
                                const std::vector<std::string>& inputs) {
  SubmissionTarget target;
  const std::optional<RecordingFrame> recording = recordingFrameOf(scenario);
  target.sequence = recording ? recording->sequence : worlds::worldName(input);
  const std::filesystem::path file = std::filesystem::path(dir) / (target.sequence + ".txt");
  target.file = common::checkOutputPath(file.string(),
                                        {common::OutputKind::kSubmission, inputs, force, true});
  return target;
}

std::pair<std::size_t, std::size_t> writeSubmission(const SubmissionTarget& target,
                                                    const bim::Scenario& scenario,
                                                    const run::RunRecord& record) {
  const bim::Route& route = scenario.robot.route;
  // The recording's stamps, in the run's clock, and the offset back to the recording's own.
  common::Trajectory poses;
  std::size_t stamps = 0;
  if (const std::optional<RecordingFrame> recording = recordingFrameOf(scenario)) {
    // Every stamp of the file, the glitches left out of the walk too.
    common::Trajectory walk_stamps;
    for (const bim::WalkPose& pose : route.walk) {
      walk_stamps.push_back({pose.t, Eigen::Isometry3d::Identity()});
    }
    for (const double t : route.bridged) walk_stamps.push_back({t, Eigen::Isometry3d::Identity()});
    std::sort(walk_stamps.begin(), walk_stamps.end(),
              [](const auto& a, const auto& b) { return a.t < b.t; });
    poses = eval::estimateAtStamps(walk_stamps, record.estimate);
    // A sensor's path: the entry is that sensor's.
    for (auto& pose : poses) {
      pose.t += recording->clock_start;
      pose.pose = pose.pose * recording->R_T_S;
    }
    stamps = walk_stamps.size();
  } else {
    poses = eval::estimateAtStamps(record.streams.ground_truth, record.estimate);
    stamps = record.streams.ground_truth.size();
  }
  const std::string text = "# timestamp tx ty tz qx qy qz qw\n" + common::toTumText(poses);
  std::error_code error;
  std::filesystem::create_directories(target.file.parent_path(), error);
  common::writeFileAtomically(target.file.string(),
                              common::outputMark(common::OutputKind::kSubmission, text));
  return {poses.size(), stamps};
}

}  // namespace isg::cli
