#include "run/dataset_reader.hpp"

#include <pcl/PCLPointCloud2.h>
#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "bim/input_error.hpp"
#include "bim/json_reader.hpp"
#include "run/dataset_format.hpp"

namespace isg::run {

namespace fs = std::filesystem;

namespace {

Trajectory readTrajectory(const fs::path& path) {
  try {
    return eval::readTum(path.string());
  } catch (const std::runtime_error& e) {
    throw bim::InputError(path.string(), "", e.what());
  }
}

}  // namespace

DatasetReader::DatasetReader(const std::string& dir) : dir_(dir) {
  const fs::path root(dir);
  if (!fs::is_directory(root))
    throw bim::InputError(dir, "", "not a dataset folder (no such directory)");
  const fs::path metadata_path = root / dataset::kMetadata;
  metadata_ = bim::readJsonFile(metadata_path.string());
  try {
    const auto& m = metadata_.at("extrinsics").at("R_T_L").at("matrix");
    Eigen::Matrix4d T;
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) T(r, c) = m.at(r).at(c).get<double>();
    }
    R_T_L_.matrix() = T;
  } catch (const nlohmann::json::exception&) {
    throw bim::InputError(metadata_path.string(), "/extrinsics/R_T_L/matrix",
                          "expected a 4 × 4 array of numbers");
  }
  odometry_ = readTrajectory(root / dataset::kOdometry);
  if (fs::exists(root / dataset::kGroundTruth))
    ground_truth_ = readTrajectory(root / dataset::kGroundTruth);
  const Trajectory stamps = readTrajectory(root / dataset::kScanPoses);
  for (const auto& entry : fs::directory_iterator(root / dataset::kScans)) {
    if (entry.path().extension() == ".pcd") scan_files_.push_back(entry.path().string());
  }
  std::sort(scan_files_.begin(), scan_files_.end());
  if (stamps.size() != scan_files_.size()) {
    throw bim::InputError((root / dataset::kScanPoses).string(), "",
                          std::to_string(stamps.size()) + " stamps for " +
                              std::to_string(scan_files_.size()) + " scans in scans/");
  }
  for (const auto& s : stamps) scan_stamps_.push_back(s.t);
  double rate = 10.0;
  if (const auto lidar = metadata_.find("lidar");
      lidar != metadata_.end() && lidar->is_object() && lidar->contains("rate_hz")) {
    const auto& value = (*lidar)["rate_hz"];
    if (!value.is_number() || !(value.get<double>() > 0.0) || !std::isfinite(value.get<double>())) {
      throw bim::InputError(metadata_path.string(), "/lidar/rate_hz", "expected a positive number");
    }
    rate = value.get<double>();
  }
  scan_period_ = 1.0 / rate;
}

SensorStreams DatasetReader::streams() const {
  SensorStreams out;
  out.ground_truth = ground_truth_;
  out.odometry = odometry_;
  out.scan_stamps = scan_stamps_;
  out.scan_period = scan_period_;
  out.R_T_L = R_T_L_;
  const double span =
      scan_stamps_.empty() ? 0.0 : scan_stamps_.back() - scan_stamps_.front() + scan_period_;
  const auto recorded = metadata_.find("duration_s");
  out.duration =
      recorded != metadata_.end() && recorded->is_number() ? recorded->get<double>() : span;
  return out;
}

slam::Scan DatasetReader::scan(int index) {
  const std::string& path = scan_files_[index];
  pcl::PCLPointCloud2 cloud;
  if (pcl::io::loadPCDFile(path, cloud) != 0) throw bim::InputError(path, "", "cannot read PCD");
  auto field = [&](const char* name) -> const pcl::PCLPointField* {
    for (const auto& f : cloud.fields) {
      if (f.name == name) return &f;
    }
    return nullptr;
  };
  const auto* x = field("x");
  const auto* y = field("y");
  const auto* z = field("z");
  const auto* time = field("time");
  if (!x || !y || !z || !time) throw bim::InputError(path, "", "needs fields x, y, z and time");
  const auto* intensity = field("intensity");
  const auto* ring = field("ring");
  auto read_float = [&](const std::uint8_t* point, const pcl::PCLPointField* f) -> float {
    if (f->datatype == pcl::PCLPointField::FLOAT32) {
      float v;
      std::memcpy(&v, point + f->offset, 4);
      return v;
    }
    if (f->datatype == pcl::PCLPointField::FLOAT64) {
      double v;
      std::memcpy(&v, point + f->offset, 8);
      return float(v);
    }
    if (f->datatype == pcl::PCLPointField::UINT16) {
      std::uint16_t v;
      std::memcpy(&v, point + f->offset, 2);
      return float(v);
    }
    throw bim::InputError(path, "", "field " + f->name + " has an unsupported type");
  };
  slam::Scan scan;
  scan.stamp = scan_stamps_[index];
  const std::size_t n = std::size_t(cloud.width) * cloud.height;
  scan.points.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t* point = cloud.data.data() + i * cloud.point_step;
    scan.points.push_back({read_float(point, x), read_float(point, y), read_float(point, z),
                           intensity ? read_float(point, intensity) : 0.0f,
                           std::uint16_t(ring ? read_float(point, ring) : 0.0f),
                           read_float(point, time)});
  }
  return scan;
}

}  // namespace isg::run
