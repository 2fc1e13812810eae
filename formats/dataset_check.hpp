#pragma once

#include "formats/dataset_reader.hpp"

namespace isg::formats {

// Checks a dataset's files against what its metadata.json says of them, before anything is made
// from it (isg export): the scan count (lidar.scans), the scan rate (lidar.scan_period_s, or
// without it lidar.rate_hz, from the stamps' mean spacing, within 1 %), the IMU's sample count and
// rate (imu.samples, imu.rate_hz, likewise) — an IMU the metadata declares must have its samples —,
// the duration (duration_s: the last scan's turn, lidar.point_time_s about its stamp, ends within
// it, and the next one would not), and scans.tum's poses against the ground truth and the LiDAR
// mount (B_T_R · R_T_L at each stamp, within 1 cm; a scans.tum shifted in time fails here). The
// first disagreement is an InputError naming the file, the metadata's JSON pointer and both
// numbers.
void checkDatasetAgainstMetadata(const DatasetReader& dataset);

}  // namespace isg::formats
