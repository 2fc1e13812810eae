#include "formats/dataset_check.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "common/input_error.hpp"
#include "formats/dataset_format.hpp"

namespace isg::formats {

namespace {

namespace fs = std::filesystem;

std::string formatNumber(double value) {
  char text[48];
  std::snprintf(text, sizeof text, "%.9g", value);
  return text;
}

// The metadata's value at a path of object keys, when it is a number.
std::optional<double> numberAt(const nlohmann::json& root,
                               std::initializer_list<const char*> keys) {
  const nlohmann::json* node = &root;
  for (const char* key : keys) {
    if (!node->is_object() || !node->contains(key)) return std::nullopt;
    node = &(*node)[key];
  }
  if (!node->is_number()) return std::nullopt;
  return node->get<double>();
}

// The mean spacing of increasing stamps; nullopt for fewer than two.
// B_T_R at `t` from the ground truth, interpolated between its rows; nullopt outside its span.
std::optional<Eigen::Vector3d> groundTruthAt(const common::Trajectory& truth, double t) {
  if (truth.empty() || t < truth.front().t - 1e-9 || t > truth.back().t + 1e-9) return std::nullopt;
  std::size_t hi = 0;
  while (hi < truth.size() && truth[hi].t < t - 1e-9) ++hi;
  if (hi == truth.size()) hi = truth.size() - 1;
  if (std::abs(truth[hi].t - t) <= 1e-9 || hi == 0) return truth[hi].pose.translation();
  const auto& a = truth[hi - 1];
  const auto& b = truth[hi];
  const double s = (t - a.t) / (b.t - a.t);
  return (1 - s) * a.pose.translation() + s * b.pose.translation();
}

}  // namespace

void checkDatasetAgainstMetadata(const DatasetReader& dataset) {
  const fs::path dir(dataset.dir());
  const std::string metadata = (dir / dataset::kMetadata).string();
  const nlohmann::json& m = dataset.metadata();
  const auto disagree = [&](const std::string& pointer, const std::string& what) {
    throw common::InputError(metadata, pointer, what);
  };

  // The LiDAR: scan count, rate and the duration they cover.
  const int scans = dataset.scanCount();
  if (const auto declared = numberAt(m, {"lidar", "scans"}); declared && *declared != scans) {
    disagree("/lidar/scans", "says " + formatNumber(*declared) + " scans, the dataset has " +
                                 std::to_string(scans) + " (scans/ and scans.tum)");
  }
  std::vector<double> stamps;
  for (int i = 0; i < scans; ++i) stamps.push_back(dataset.scanStamp(i));
  if (const auto declared = numberAt(m, {"lidar", "scan_period_s"})) {
    if (const auto period = dataset::meanPeriod(stamps);
        period && std::abs(*period / *declared - 1.0) > 0.01) {
      disagree("/lidar/scan_period_s", "says " + formatNumber(*declared) +
                                           " s, scans.tum's stamps are " + formatNumber(*period) +
                                           " s apart on average");
    }
  }
  // A cloud a turn (the default angle cut): the stamps come at the rotation rate.
  const bool cut_by_angle = !(m.is_object() && m.contains("lidar") && m["lidar"].is_object() &&
                              m["lidar"].contains("cut") && m["lidar"]["cut"] != "angle");
  if (const auto rate = numberAt(m, {"lidar", "rate_hz"}); rate && cut_by_angle) {
    if (const auto period = dataset::meanPeriod(stamps);
        period && std::abs(*period * *rate - 1.0) > 0.01) {
      disagree("/lidar/rate_hz", "says " + formatNumber(*rate) + " Hz, scans.tum's stamps are " +
                                     formatNumber(1.0 / *period) + " Hz apart on average");
    }
  }
  // scans.tum: the LiDAR's pose at each stamp, which the ground truth and the mount also give.
  const common::Trajectory& truth = dataset.groundTruth();
  const common::Trajectory& poses = dataset.scanPoses();
  for (std::size_t i = 0; i < poses.size() && !truth.empty(); ++i) {
    const auto B_p_R = groundTruthAt(truth, poses[i].t);
    const std::string file = (dir / dataset::kScanPoses).string();
    if (!B_p_R) {
      throw common::InputError(file, "",
                               "scan " + std::to_string(i) + " at " + formatNumber(poses[i].t) +
                                   " s lies outside the ground truth's time span");
    }
    // The mount's offset turned by the base's orientation at that time: from the nearest row.
    std::size_t k = 0;
    while (k + 1 < truth.size() && truth[k + 1].t <= poses[i].t + 1e-9) ++k;
    const Eigen::Vector3d expected =
        *B_p_R + truth[k].pose.linear() * dataset.R_T_L().translation();
    const double off = (poses[i].pose.translation() - expected).norm();
    if (off > 0.01) {
      throw common::InputError(file, "",
                               "scan " + std::to_string(i) + " at " + formatNumber(poses[i].t) +
                                   " s: the LiDAR pose is " + formatNumber(off) +
                                   " m from the ground truth's (" + dataset::kGroundTruth +
                                   " and the mount in metadata.json): the files do not belong "
                                   "together");
    }
  }

  if (const auto duration = numberAt(m, {"duration_s"}); duration && !stamps.empty()) {
    // Every scan's turn ends within the duration, and one more turn would not have.
    const double period = dataset.scanPeriod();
    const double last_end = stamps.back() + dataset.turnEndFromStamp();
    if (last_end > *duration + 1e-6 || last_end + period <= *duration - 1e-6) {
      disagree("/duration_s", "says " + formatNumber(*duration) +
                                  " s, the last scan's turn ends at " + formatNumber(last_end) +
                                  " s");
    }
  }

  // The IMU: declared samples must be there, as many as said, at the rate said.
  if (m.is_object() && m.contains("imu")) {
    const auto& imu = dataset.imu();
    const std::string imu_file = (dir / dataset::kImu).string();
    if (const auto samples = numberAt(m, {"imu", "samples"})) {
      if (*samples > 0 && imu.empty()) {
        disagree("/imu/samples", "says " + formatNumber(*samples) + " samples, " + imu_file +
                                     (fs::exists(imu_file) ? " has none" : " does not exist"));
      }
      if (*samples != double(imu.size())) {
        disagree("/imu/samples", "says " + formatNumber(*samples) + " samples, " + imu_file +
                                     " has " + std::to_string(imu.size()));
      }
    }
    if (const auto rate = numberAt(m, {"imu", "rate_hz"})) {
      std::vector<double> imu_stamps;
      for (const auto& s : imu) imu_stamps.push_back(s.t);
      if (const auto period = dataset::meanPeriod(imu_stamps);
          period && std::abs(*period * *rate - 1.0) > 0.01) {
        disagree("/imu/rate_hz", "says " + formatNumber(*rate) + " Hz, " + imu_file +
                                     "'s samples are " + formatNumber(1.0 / *period) +
                                     " Hz apart on average");
      }
    }
  }
}

}  // namespace isg::formats
