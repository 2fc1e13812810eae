#pragma once

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "sensors/messages.hpp"
#include "sensors/sensor_streams.hpp"

namespace isg::formats {

// The dataset folder (docs/formats.md, "Datasets"): what `isg simulate` writes and `isg slam`
// replays. The writer (sim/dataset_writer) and the reader (sensors/dataset_reader) share these
// names and encodings, so the format is defined once.
namespace dataset {

inline constexpr const char* kMetadata = "metadata.json";
inline constexpr const char* kGroundTruth = "groundtruth.tum";  // B_T_R
inline constexpr const char* kOdometry = "odometry.tum";        // M_T_R
inline constexpr const char* kScanPoses = "scans.tum";          // B_T_L at each scan stamp
// Without ground truth (an imported recording) the scans' stamps alone, one a line.
inline constexpr const char* kScanStamps = "scans.txt";
inline constexpr const char* kScans = "scans";  // scans/NNNNNN.pcd
inline constexpr const char* kImu = "imu.csv";  // the IMU stream, in I
inline constexpr const char* kFormat = "isg.dataset";
inline constexpr int kVersion = 1;

// "000042.pcd": scans sort by name in time order.
std::string scanFileName(int index);

// The mean time between consecutive stamps (in order); none for fewer than two.
std::optional<double> meanPeriod(const std::vector<double>& stamps);

// A trajectory file's text (TUM, common::toTumText).
std::string trajectoryText(const common::Trajectory& trajectory);

// scans.txt's text: one time a line, in seconds with nine decimals (TUM's time column).
std::string stampsText(const std::vector<double>& stamps);

// imu.csv's text: the header line "t,ax,ay,az,gx,gy,gz", then one line per sample (seconds,
// m/s², rad/s; nine significant digits).
std::string imuText(const std::vector<sensors::ImuSample>& samples);

// How a scan's PCD file stores its points: "binary" (point after point, 22 bytes each) or
// "binary_compressed" (PCL's: field after field, LZF-compressed; about 0.8 of the size on
// simulated scans, whose float mantissas do not compress)).
enum class PcdData { kBinary, kBinaryCompressed };
inline constexpr PcdData kDefaultPcdData = PcdData::kBinaryCompressed;
const char* pcdDataName(PcdData data);  // the PCD header's word: "binary", "binary_compressed"

// A scan as PCD v0.7 with the Velodyne driver's point layout: fields x y z intensity (float32)
// ring (uint16) time (float32, seconds from the scan stamp), in the LiDAR frame.
std::string pcdBytes(const std::vector<sensors::ScanPoint>& points, PcdData data);
inline std::string pcdBinary(const std::vector<sensors::ScanPoint>& points) {
  return pcdBytes(points, PcdData::kBinary);
}

// A sensor's mount on the base as metadata.json gives it: {"xyz_rpy": [...], "matrix": 4×4 rows}.
nlohmann::ordered_json mountJson(const std::array<double, 6>& xyz_rpy, const Eigen::Isometry3d& T);
// metadata.json's "extrinsics" entry: {"R_T_L": mountJson(...)}.
nlohmann::ordered_json extrinsicsJson(const std::array<double, 6>& xyz_rpy,
                                      const Eigen::Isometry3d& R_T_L);

}  // namespace dataset
}  // namespace isg::formats
