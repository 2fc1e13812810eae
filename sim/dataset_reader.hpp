#pragma once

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "eval/tum.hpp"
#include "slam/messages.hpp"

namespace isg::sim {

// A dataset folder (docs/simulation.md) opened for replay: metadata, odometry and ground truth
// at once, scans one at a time. Any dataset in the format, not only ours: PCD fields are found
// by name. Problems are InputErrors naming the file.
class DatasetReader {
 public:
  explicit DatasetReader(const std::string& dir);

  const nlohmann::json& metadata() const { return metadata_; }
  const Eigen::Isometry3d& R_T_L() const { return R_T_L_; }
  const eval::Trajectory& odometry() const { return odometry_; }
  const eval::Trajectory& groundTruth() const { return ground_truth_; }
  int scanCount() const { return int(scan_files_.size()); }
  double scanStamp(int index) const { return scan_stamps_[index]; }
  slam::Scan scan(int index) const;

 private:
  std::string dir_;
  nlohmann::json metadata_;
  Eigen::Isometry3d R_T_L_ = Eigen::Isometry3d::Identity();
  eval::Trajectory odometry_, ground_truth_;
  std::vector<std::string> scan_files_;
  std::vector<double> scan_stamps_;
};

}  // namespace isg::sim
