#pragma once

#include <Eigen/Geometry>
#include <functional>
#include <vector>

#include "common/pose_track.hpp"
#include "sensors/messages.hpp"

namespace isg::sensors {

// Everything a run feeds a localizer besides the scans themselves, and what it is judged
// against: the same whether it comes from the live simulation or from a recorded dataset. The
// trajectories hold exactly the numbers a dataset's TUM files carry (quantiseStreams), so that a
// replay sees what the live loop saw. They are held for the whole run (the evaluation reads them
// at its end), in 36 bytes a pose (common::PoseTrack).
struct SensorStreams {
  common::PoseTrack ground_truth;  // B_T_R
  // M_T_R, as the localizer gets it; empty: none (handheld, or a recording).
  common::PoseTrack odometry;
  std::vector<double> scan_stamps;                          // each scan's first firing
  double scan_period = 0.1;                                 // seconds per LiDAR turn
  double duration = 0.0;                                    // seconds of robot time the run covers
  Eigen::Isometry3d R_T_L = Eigen::Isometry3d::Identity();  // the LiDAR on the base
  // The IMU, in its frame I, and its mount: a replayed dataset's imu.csv, or the live
  // simulation's stream with the same digits.
  std::vector<sensors::ImuSample> imu;
  // When set, the IMU is made as the run reads it (the live simulation: hours of it are ~80 MB):
  // `imu` holds its first samples, and each call gives the next ones, none once it is over.
  std::function<std::vector<sensors::ImuSample>()> imu_more;
  Eigen::Isometry3d R_T_I = Eigen::Isometry3d::Identity();
};

// Rounds ground truth, odometry and scan stamps to what their TUM files keep (common::quantised).
// The live producer (sim::sensorStreams) rounds each pose as it stores it
// (common::PoseTrack::pushQuantised, the same numbers); a dataset's streams come from the files
// and are quantised already; streams made otherwise are rounded with this.
void quantiseStreams(SensorStreams& streams);

// Where the odometry frame M lies in the plan B at the start: the first ground-truth pose times
// the inverse of the first odometry pose. What dead reckoning is given and what the evaluation
// places odometry with. Without odometry, the first ground-truth pose levelled (where the odometry
// the LiDAR and the IMU make starts: slam::ScanOdometry). Identity without ground truth.
// Where M lies in B when the base's first pose is B_T_R0: B_T_R0 times the inverse of the
// odometry's first pose, or — without odometry, where M is the first pose levelled — B_T_R0's
// position and heading.
Eigen::Isometry3d startB_T_M(const SensorStreams& streams, const Eigen::Isometry3d& B_T_R0);
Eigen::Isometry3d trueStartB_T_M(const SensorStreams& streams);

}  // namespace isg::sensors
