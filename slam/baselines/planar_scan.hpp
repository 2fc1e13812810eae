#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "sensors/messages.hpp"

namespace isg::slam {

// A 2D laser scan made from a 3D one, as pointcloud_to_laserscan does for 2D localizers: the
// points within a height band around the sensor, binned by bearing, the nearest kept per bin.
struct PlanarScanOptions {
  double band = 0.25;  // metres above and below the sensor's height, in the base frame
  double bearing_step_deg = 1.0;
  double min_range = 0.3;    // closer points are the robot itself
  double max_range = 100.0;  // the VLP-16's
};

struct PlanarScan {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  // the sensor in the base frame R (x, y)
  // The beams' end points in R (x, y), by increasing bearing; empty bins have none.
  std::vector<Eigen::Vector2d> endpoints;
  std::vector<double> ranges;  // from origin, one per end point
};

PlanarScan planarScan(const sensors::Scan& scan, const Eigen::Isometry3d& R_T_L,
                      const PlanarScanOptions& options = {});

}  // namespace isg::slam
