#include "recordings/bag_import_parts.hpp"

namespace isg::recordings::bag_import {

void Import::takeTfOdometry() {
  if (!tf_odometry_) return;
  for (const auto& pose : tf_odometry_->poses()) odometry_.push_back({pose.stamp, pose.top_T_base});
  if (odometry_.empty()) {
    fail("topic " + summary_.odometry.topic + ": no transform of the chain " +
         summary_.odometry_chain + " in the part imported");
  }
  if (tf_odometry_->repeated() > 0) {
    summary_.notes.push_back(std::to_string(tf_odometry_->repeated()) +
                             " transforms of the odometry's chain repeat their link's previous "
                             "stamp: left out");
  }
}

std::vector<sensors::ImuSample> Import::imuInDatasetTime() {
  std::vector<sensors::ImuSample> imu;
  for (const auto& s : imu_) {
    sensors::ImuSample sample = s.sample;
    sample.t = seconds(s.stamp);
    imu.push_back(sample);
  }
  if (imu.empty()) return imu;
  // The IMU's units: m/s² unless the specific force's median norm over the first second says g.
  std::vector<double> norms;
  for (const auto& s : imu) {
    if (s.t > imu.front().t + 1.0) break;
    norms.push_back(s.accelerometer.norm());
  }
  std::nth_element(norms.begin(), norms.begin() + norms.size() / 2, norms.end());
  const double median = norms[norms.size() / 2];
  if (std::abs(median - 1.0) < kGravityInG) {
    for (auto& s : imu) s.accelerometer *= kStandardGravity;
    imu_variance_[1] *= kStandardGravity * kStandardGravity;
    char line[160];
    std::snprintf(line, sizeof line,
                  "the IMU's specific force is in g (median norm %.3f over its first second): "
                  "converted to m/s²",
                  median);
    summary_.notes.push_back(line);
  }
  return imu;
}

std::vector<double> Import::scansWithinOdometry(const fs::path& folder,
                                                const common::Trajectory& odometry) {
  std::vector<double> stamps;
  for (const auto& s : scan_stamps_) stamps.push_back(seconds(s));
  std::size_t first = 0, last = stamps.size();
  if (!odometry.empty()) {
    while (first < last && stamps[first] < odometry.front().t) ++first;
    while (last > first && stamps[last - 1] > odometry.back().t) --last;
    if (first == last) {
      fail("no cloud on " + summary_.lidar.topic + " lies within the odometry's time span (" +
           summary_.odometry.topic + ")");
    }
    if (first > 0 || last < stamps.size()) {
      summary_.notes.push_back(std::to_string(first + stamps.size() - last) +
                               " clouds outside the odometry's time span left out");
    }
  }
  const fs::path scans = folder / formats::dataset::kScans;
  for (std::size_t i = 0; i < stamps.size(); ++i) {
    const fs::path file = scans / formats::dataset::scanFileName(int(i));
    if (i < first || i >= last) {
      fs::remove(file);
    } else if (first > 0) {
      fs::rename(file, scans / formats::dataset::scanFileName(int(i - first)));
    }
  }
  return std::vector<double>(stamps.begin() + std::ptrdiff_t(first),
                             stamps.begin() + std::ptrdiff_t(last));
}

void Import::writeScanTimes(const fs::path& folder, const std::vector<double>& stamps,
                            const common::Trajectory& truth) {
  // scans.tum when the ground truth covers every scan, else the stamps alone.
  common::Trajectory scan_poses;
  for (double t : stamps) {
    const auto B_T_R = common::interpolatePose(truth, t);
    if (!B_T_R) break;
    scan_poses.push_back({t, *B_T_R * R_T_L_});
  }
  if (!truth.empty() && scan_poses.size() == stamps.size()) {
    common::writeFile(folder / formats::dataset::kScanPoses,
                      formats::dataset::trajectoryText(scan_poses));
    return;
  }
  if (!truth.empty()) {
    summary_.notes.push_back(
        "the ground truth does not cover every scan: scans.txt holds "
        "their stamps, without poses");
  }
  common::writeFile(folder / formats::dataset::kScanStamps, formats::dataset::stampsText(stamps));
}

void Import::writeFiles(const fs::path& folder) {
  takeTfOdometry();
  // Dataset time 0: the whole second at or before the first imported stamp.
  origin_ = scan_stamps_.front().sec;
  for (const auto& s : imu_) origin_ = std::min(origin_, s.stamp.sec);
  for (const auto* poses : {&odometry_, &truth_}) {
    if (!poses->empty()) origin_ = std::min(origin_, poses->front().stamp.sec);
  }
  common::Trajectory odometry, truth;
  for (const auto& p : odometry_) odometry.push_back({seconds(p.stamp), p.pose * odometry_C_T_R_});
  for (const auto& p : truth_) truth.push_back({seconds(p.stamp), p.pose * truth_C_T_R_});
  const std::vector<sensors::ImuSample> imu = imuInDatasetTime();
  // Scans outside the odometry's span would have no motion prior: left out.
  const std::vector<double> stamps = scansWithinOdometry(folder, odometry);
  summary_.lidar.messages = stamps.size();
  summary_.imu.messages = imu.size();
  summary_.odometry.messages = odometry.size();
  summary_.ground_truth.messages = truth.size();
  // The turn about its stamp.
  summary_.scan_period = formats::dataset::meanPeriod(stamps).value_or(0.1);
  summary_.point_time = clouds_with_time_ > 0 && time_max_ > time_min_
                            ? std::array<double, 2>{time_min_, time_max_}
                            : std::array<double, 2>{0.0, summary_.scan_period};
  summary_.stamp = 2 * clouds_stamped_at_end_ > clouds_with_time_ ? "last_packet" : "first_firing";
  summary_.cloud_layout =
      packets_ ? "x y z intensity ring time (VLP-16 packets decoded)" : layout_.describe();
  if (packets_) {
    const char* mode = packet_mode_ == formats::Vlp16ReturnMode::kDual   ? "dual"
                       : packet_mode_ == formats::Vlp16ReturnMode::kLast ? "last"
                                                                         : "strongest";
    summary_.notes.push_back(common::counted(packet_count_, "VLP-16 packet") + " decoded (" + mode +
                             " return) into " + common::counted(scan_stamps_.size(), "turn") +
                             " cut at azimuth 0; the first and the last turn, cut short, left out" +
                             (weak_echoes_ > 0 ? "; the weaker echo of " +
                                                     common::counted(weak_echoes_, "shot") +
                                                     " left out (one return a shot)"
                                               : ""));
  }
  summary_.seconds = stamps.back() + summary_.point_time[1];

  writeScanTimes(folder, stamps, truth);
  if (!odometry.empty())
    common::writeFile(folder / formats::dataset::kOdometry,
                      formats::dataset::trajectoryText(odometry));
  if (!truth.empty())
    common::writeFile(folder / formats::dataset::kGroundTruth,
                      formats::dataset::trajectoryText(truth));
  if (!imu.empty())
    common::writeFile(folder / formats::dataset::kImu, formats::dataset::imuText(imu));
  common::writeFile(folder / formats::dataset::kMetadata,
                    datasetMetadata(stamps, imu, odometry).dump(2) + "\n");
}

nlohmann::ordered_json Import::datasetMetadata(const std::vector<double>& stamps,
                                               const std::vector<sensors::ImuSample>& imu,
                                               const common::Trajectory& odometry) {
  nlohmann::ordered_json m;
  if (isg_metadata_) {
    // An isg dataset exported to a bag: its own metadata back, counts and span as imported.
    summary_.from_isg = true;
    m = formats::dataset::inMetadataOrder(nlohmann::ordered_json::parse(isg_metadata_->dump()));
    if (options_.start > 0 || options_.duration) {
      m["duration_s"] = summary_.seconds;
      m["lidar"]["scans"] = stamps.size();
      if (m.contains("imu") && m["imu"].is_object()) m["imu"]["samples"] = imu.size();
    }
    m["lidar"]["pcd_data"] = formats::dataset::pcdDataName(formats::dataset::kDefaultPcdData);
  } else {
    m = metadata(stamps, imu, odometry);
  }
  m["imported_from"] = {{"file", fs::path(bag_path_).filename().string()},
                        {"start_s", options_.start},
                        {"time_origin_s", origin_},
                        {"topics",
                         {{"lidar", summary_.lidar.topic},
                          {"imu", summary_.imu.topic},
                          {"odometry", summary_.odometry.topic},
                          {"ground_truth", summary_.ground_truth.topic}}},
                        {"notes", summary_.notes}};
  if (options_.duration) m["imported_from"]["duration_s"] = *options_.duration;
  return m;
}

nlohmann::ordered_json Import::metadata(const std::vector<double>& stamps,
                                        const std::vector<sensors::ImuSample>& imu,
                                        const common::Trajectory& odometry) const {
  formats::dataset::Metadata m;
  m.generator = std::string("isg import ") + common::kProjectVersion;
  m.duration_s = summary_.seconds;
  m.frames = {{"B", truth_frame_.empty() ? "plan frame (no ground truth recorded)" : truth_frame_},
              {"M", odometry_frame_.empty() ? "odometry frame (none recorded)" : odometry_frame_},
              {"R", base_frame_},
              {"L", lidar_frame_},
              {"I", imu_frame_.empty() ? "(no IMU recorded)" : imu_frame_}};
  m.lidar_mount = sensors::mountXyzRpy(R_T_L_);
  m.R_T_L = R_T_L_;
  m.lidar = {"recorded",
             1.0 / summary_.scan_period,
             stamps.size(),
             summary_.stamp,
             summary_.scan_period,
             summary_.point_time,
             formats::dataset::kDefaultPcdData};
  nlohmann::ordered_json description = {{"lidar", {{"fields", summary_.cloud_layout}}}};
  if (!imu.empty()) {
    m.imu_mount = {sensors::mountXyzRpy(R_T_I_), R_T_I_};
    std::vector<double> times;
    for (const auto& s : imu) times.push_back(s.t);
    const double rate = imu.size() >= 2 ? 1.0 / *formats::dataset::meanPeriod(times) : 0.0;
    m.imu = formats::dataset::Metadata::Imu{rate, imu.size(), std::nullopt, std::nullopt};
    // The message's per-sample variances are density² × rate; given only when the driver
    // filled them.
    if (imu_variance_[0] > 0 && imu_variance_[1] > 0 && rate > 0) {
      m.imu->gyroscope_noise_density = std::sqrt(imu_variance_[0] / rate);
      m.imu->accelerometer_noise_density = std::sqrt(imu_variance_[1] / rate);
    }
  }
  if (!odometry.empty()) {
    std::vector<double> times;
    for (const auto& p : odometry) times.push_back(p.t);
    m.odometry = {times.size() >= 2 ? 1.0 / *formats::dataset::meanPeriod(times) : 0.0};
    description["odometry"] = {{"topic", summary_.odometry.topic}};
    if (tf_odometry_) description["odometry"]["chain"] = summary_.odometry_chain;
  }
  return formats::dataset::metadataJson(m, description);
}

}  // namespace isg::recordings::bag_import
