#include "formats/dataset_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>

#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "formats/dataset_format.hpp"
#include "formats/imu_file.hpp"
#include "formats/pcd_reader.hpp"
#include "formats/trajectory_file.hpp"

namespace isg::formats {

namespace fs = std::filesystem;

namespace {

// A sensor's mount from metadata.json: a rigid transform (a rotation, orthonormal with
// determinant +1, and a last row of 0 0 0 1) within 10 m. Anything else (an all-zero matrix)
// would poison every point and the optimiser with it.
Eigen::Isometry3d mountOf(const common::JsonNode& matrix, const std::string& sensor) {
  const auto rows = matrix.elements();
  if (rows.size() != 4) matrix.fail("expected a 4 × 4 array of numbers");
  Eigen::Matrix4d T;
  for (int r = 0; r < 4; ++r) {
    const auto row = rows[std::size_t(r)].numbers(4);
    for (int c = 0; c < 4; ++c) T(r, c) = row[std::size_t(c)];
  }
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  const double orthogonality =
      (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (orthogonality > 1e-6 || R.determinant() < 0.5) {
    matrix.fail("the upper-left 3 × 3 block is not a rotation (orthonormal with determinant +1)");
  }
  if ((T.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-9) {
    matrix.fail("the last row must be 0 0 0 1");
  }
  if (T.col(3).head<3>().cwiseAbs().maxCoeff() > 10.0) {
    matrix.fail("the " + sensor + " must be mounted within 10 m of the robot's reference point");
  }
  Eigen::Isometry3d out;
  out.matrix() = T;
  return out;
}

// The scan file of each stamp: stamp k's scan is scans/NNNNNN.pcd with NNNNNN = k (six digits or
// more, dataset::scanFileName). Scans are matched by name, never by position in a sorted listing:
// a renamed or missing file would otherwise shift every later scan onto the previous stamp. The
// first stamp without its file, else the first .pcd file no stamp names, is an InputError.
std::vector<std::string> scanFilesOf(const fs::path& scans, const std::string& stamps_file,
                                     const common::Trajectory& stamps) {
  std::error_code error;
  if (!fs::is_directory(scans, error)) {
    throw common::InputError(scans.string(), "",
                             "not a folder: a dataset keeps its LiDAR scans in scans/");
  }
  std::vector<std::string> files;
  std::set<std::string> expected;
  for (std::size_t k = 0; k < stamps.size(); ++k) {
    files.push_back((scans / dataset::scanFileName(int(k))).string());
    expected.insert(dataset::scanFileName(int(k)));
  }
  std::vector<std::string> extra;
  std::size_t found = 0;
  for (const auto& entry : fs::directory_iterator(scans)) {
    if (entry.path().extension() != ".pcd") continue;
    if (expected.count(entry.path().filename().string()) != 0) {
      ++found;
    } else {
      extra.push_back(entry.path().filename().string());
    }
  }
  std::sort(extra.begin(), extra.end());
  const std::string rule = "scan k is scans/NNNNNN.pcd, k from 000000 in " +
                           fs::path(stamps_file).filename().string() + "'s order";
  const std::string counts = std::to_string(stamps.size()) + " stamps, " +
                             std::to_string(found + extra.size()) + " .pcd files in scans/";
  for (std::size_t k = 0; k < stamps.size(); ++k) {
    if (fs::is_regular_file(files[k], error)) continue;
    char stamp[64];
    std::snprintf(stamp, sizeof stamp, "%.9f", stamps[k].t);
    throw common::InputError(
        files[k], "",
        "missing: no scan for stamp " + std::to_string(k) + " (t = " + stamp + " s in " +
            stamps_file + "; " + rule + "; " + counts +
            (extra.empty() ? "" : "; scans/" + extra.front() + " is no stamp's scan") + ")");
  }
  if (!extra.empty()) {
    throw common::InputError(
        (scans / extra.front()).string(), "",
        "no stamp's scan: " + rule + ", and " + stamps_file + " has " +
            (stamps.empty()
                 ? "no stamps"
                 : std::to_string(stamps.size()) + " stamps (" + dataset::scanFileName(0) + " to " +
                       dataset::scanFileName(int(stamps.size()) - 1) + ")"));
  }
  return files;
}

}  // namespace

void DatasetReader::readMetadata(const std::string& file) {
  const common::JsonSource source{file, nullptr};
  const common::JsonNode root(metadata_, "", source);
  if (!root.isObject()) root.fail("expected an object, got " + common::describeJsonType(metadata_));
  R_T_L_ = mountOf(root.field("extrinsics").field("R_T_L").field("matrix"), "LiDAR");
  if (auto imu = root.field("extrinsics").optionalField("R_T_I")) {
    R_T_I_ = mountOf(imu->field("matrix"), "IMU");
  }
  // The IMU's noise, when the dataset knows it (a recording's driver may not say).
  if (auto imu = root.optionalField("imu"); imu && imu->optionalField("gyroscope_noise_density")) {
    ImuNoise noise;
    noise.rate_hz = imu->field("rate_hz").numberInRange(1.0, 100000.0);
    noise.gyroscope_noise_density = imu->field("gyroscope_noise_density").numberInRange(0.0, 1e3);
    noise.accelerometer_noise_density =
        imu->field("accelerometer_noise_density").numberInRange(0.0, 1e3);
    imu_noise_ = noise;
  }
  if (auto lidar = root.optionalField("lidar")) {
    if (auto rate = lidar->optionalField("rate_hz"))
      scan_period_ = 1.0 / rate->numberInRange(0.1, 1000.0);
    if (auto period = lidar->optionalField("scan_period_s"))
      scan_period_ = period->numberInRange(0.001, 10.0);
    point_time_ = {0.0, scan_period_};
    if (auto span = lidar->optionalField("point_time_s")) {
      const std::vector<double> range = span->numbers(2);
      if (!(range[0] < range[1]) || range[1] - range[0] > 10.0 || std::abs(range[0]) > 10.0) {
        span->fail(
            "expected [first, last] seconds about the stamp, first below last, "
            "within 10 s");
      }
      point_time_ = {range[0], range[1]};
    }
  }
  if (auto seed = root.optionalField("seed")) seed_ = seed->unsignedInteger();
  if (auto duration = root.optionalField("duration_s")) {
    duration_ = duration->numberInRange(0.0, 1e7);
  }
  if (auto robot = root.optionalField("robot")) {
    if (auto level = robot->optionalField("level")) robot_level_ = level->identifier();
  }
  if (auto plan = root.optionalField("plan")) {
    if (!plan->isObject())
      plan->fail("expected the plan object, got " + common::describeJsonType(plan->raw()));
  }
}

DatasetReader::DatasetReader(const std::string& dir) : dir_(dir) {
  const fs::path root(dir);
  if (!fs::is_directory(root))
    throw common::InputError(dir, "", "not a dataset folder (no such directory)");
  const fs::path metadata_path = root / dataset::kMetadata;
  metadata_ = common::readJsonFile(metadata_path.string());
  readMetadata(metadata_path.string());
  // A recording imported without odometry (a handheld sensor) has none.
  if (fs::exists(root / dataset::kOdometry))
    odometry_ = readTrajectoryFile((root / dataset::kOdometry).string());
  if (fs::exists(root / dataset::kGroundTruth))
    ground_truth_ = readTrajectoryFile((root / dataset::kGroundTruth).string());
  // The scans' stamps: with the LiDAR's pose (scans.tum), or alone when there is no ground truth
  // (scans.txt).
  common::Trajectory stamps;
  std::string stamps_file = (root / dataset::kScanPoses).string();
  if (!fs::exists(stamps_file) && fs::exists(root / dataset::kScanStamps)) {
    stamps_file = (root / dataset::kScanStamps).string();
    for (double t : readStampsFile(stamps_file))
      stamps.push_back({t, Eigen::Isometry3d::Identity()});
  } else {
    stamps = readTrajectoryFile(stamps_file);
    scan_poses_ = stamps;
  }
  scan_files_ = scanFilesOf(root / dataset::kScans, stamps_file, stamps);
  for (const auto& s : stamps) scan_stamps_.push_back(s.t);
  if (fs::exists(root / dataset::kImu)) imu_ = readImuFile((root / dataset::kImu).string());
}

sensors::SensorStreams DatasetReader::streams() const {
  sensors::SensorStreams out;
  out.ground_truth = ground_truth_;
  out.odometry = odometry_;
  out.scan_stamps = scan_stamps_;
  out.scan_period = scan_period_;
  out.R_T_L = R_T_L_;
  out.imu = imu_;
  out.R_T_I = R_T_I_;
  out.duration = duration();
  return out;
}

double DatasetReader::duration() const {
  const double span =
      scan_stamps_.empty() ? 0.0 : scan_stamps_.back() - scan_stamps_.front() + scan_period_;
  return duration_.value_or(span);
}

sensors::Scan DatasetReader::scan(int index) {
  sensors::StageClock clock(times_, "reading scans");
  sensors::Scan scan;
  scan.stamp = scan_stamps_[std::size_t(index)];
  scan.points = readPcd(scan_files_[std::size_t(index)]);
  return scan;
}

void DatasetReader::skip(int index) {
  sensors::StageClock clock(times_, "reading scans");
  readPcd(scan_files_[std::size_t(index)]);
}

}  // namespace isg::formats
