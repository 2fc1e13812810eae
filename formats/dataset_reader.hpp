#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "sensors/messages.hpp"
#include "sensors/scan_source.hpp"
#include "sensors/sensor_streams.hpp"

namespace isg::formats {

// A dataset folder (sensors/dataset_format.hpp, docs/formats.md) opened for replay: metadata,
// odometry and ground truth at once, scans one at a time. Any dataset in the format, not only
// ours: PCD fields are found by name. Problems are InputErrors naming the file.
class DatasetReader : public sensors::ScanSource {
 public:
  explicit DatasetReader(const std::string& dir);

  const nlohmann::json& metadata() const { return metadata_; }
  const std::string& dir() const { return dir_; }
  // Checked fields of metadata.json (docs/formats.md): the run's seed (0 when not recorded) and
  // the robot's level (empty when not recorded).
  std::uint64_t seed() const { return seed_; }
  const std::string& robotLevel() const { return robot_level_; }
  const Eigen::Isometry3d& R_T_L() const { return R_T_L_; }
  // The IMU's mount (extrinsics.R_T_I; identity when not recorded) and its stream (imu.csv;
  // empty when the dataset has none).
  const Eigen::Isometry3d& R_T_I() const { return R_T_I_; }
  const std::vector<sensors::ImuSample>& imu() const { return imu_; }
  // metadata.json's imu noise model, when recorded: what a consumer's covariances come from.
  struct ImuNoise {
    double rate_hz = 0.0;
    double gyroscope_noise_density = 0.0;      // rad/s/√Hz
    double accelerometer_noise_density = 0.0;  // m/s²/√Hz
  };
  const std::optional<ImuNoise>& imuNoise() const { return imu_noise_; }
  // odometry.tum (empty when the dataset has none: an imported handheld recording).
  const common::Trajectory& odometry() const { return odometry_; }
  const common::Trajectory& groundTruth() const { return ground_truth_; }
  int scanCount() const { return int(scan_files_.size()); }
  double scanStamp(int index) const { return scan_stamps_[index]; }
  // scans.tum: B_T_L at each scan's stamp (empty when the dataset has scans.txt, stamps alone).
  const common::Trajectory& scanPoses() const { return scan_poses_; }
  // Seconds between two scans (metadata lidar.scan_period_s, else 1 / lidar.rate_hz; 0.1 s when
  // neither is given).
  double scanPeriod() const { return scan_period_; }
  // The span of the points' `time` about their scan's stamp (metadata lidar.point_time_s; from 0
  // to the scan period when not given): where a turn starts and ends about its stamp.
  double turnStartFromStamp() const { return point_time_[0]; }
  double turnEndFromStamp() const { return point_time_[1]; }
  // What the run's driver is fed: the dataset's streams, with the duration the metadata records
  // (duration_s) or, without it, the scans' span.
  sensors::SensorStreams streams() const;
  // The duration streams() carries, without copying the streams.
  double duration() const;
  sensors::Scan scan(int index) override;
  // A scan the localizer will not read is still read and checked: a damaged file is reported
  // whichever scans the method reads, and a replay gives the same verdict for every method.
  void skip(int index) override;
  sensors::StageTimes stageTimes() const override { return times_; }

 private:
  void readMetadata(const std::string& file);

  std::string dir_;
  nlohmann::json metadata_;
  std::uint64_t seed_ = 0;
  std::string robot_level_;
  std::optional<double> duration_;
  common::Trajectory scan_poses_;
  Eigen::Isometry3d R_T_L_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d R_T_I_ = Eigen::Isometry3d::Identity();
  std::vector<sensors::ImuSample> imu_;
  std::optional<ImuNoise> imu_noise_;
  common::Trajectory odometry_, ground_truth_;
  double scan_period_ = 0.1;
  std::array<double, 2> point_time_ = {0.0, 0.1};
  std::vector<std::string> scan_files_;
  std::vector<double> scan_stamps_;
  sensors::StageTimes times_;  // "reading scans"
};

}  // namespace isg::formats
