#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sensors/lidar_model.hpp"
#include "sensors/messages.hpp"

namespace isg::formats {

// One PointField of a packed cloud (datatype as sensor_msgs/PointField numbers it).
struct CloudField {
  const char* name;
  std::uint32_t offset;
  std::uint8_t datatype;
};

// A cloud's points packed as a ROS driver publishes them: its fields, the bytes a point takes and
// the points' bytes (little-endian, one row, every point a return).
struct PackedCloud {
  std::vector<CloudField> fields;
  std::uint32_t point_step = 0;
  std::string data;
};

// Which driver's layout an exported cloud takes (docs/formats.md, "ROS bags"), and
// the driver's ring number of each ring by elevation (empty: the rings as they are).
struct CloudConvention {
  sensors::DriverCloudLayout layout = sensors::DriverCloudLayout::kVelodyne;
  std::vector<std::uint16_t> driver_rings;
  // The layout and ring numbers of `model`'s driver.
  static CloudConvention of(const sensors::LidarModel& model);
};

// `points` (times in seconds from the stamp, rings by elevation) in `convention`'s layout:
//   Velodyne: x y z intensity (float32 at 0, 4, 8, 12), ring (uint16 at 16), time (float32 at 18,
//     s from the stamp); 22 bytes.
//   Hesai: x y z (float32 at 0, 4, 8), intensity (float32 at 16), timestamp (float64 at 24, s
//     since the epoch: the stamp plus the point's time), ring (uint16 at 32); 48 bytes, as the
//     SDK's aligned PointXYZIT.
//   Ouster: x y z (float32 at 0, 4, 8), intensity (float32 at 16), t (uint32 at 20, ns from the
//     stamp), reflectivity (uint16 at 24, the intensity rounded), ring (uint16 at 26), ambient
//     (uint16 at 28, 0: not simulated), range (uint32 at 32, mm from the sensor's origin); 48
//     bytes, as ouster-ros's aligned Point.
PackedCloud packCloud(const std::vector<sensors::ScanPoint>& points,
                      const CloudConvention& convention, std::uint32_t stamp_sec,
                      std::uint32_t stamp_nsec);

}  // namespace isg::formats
