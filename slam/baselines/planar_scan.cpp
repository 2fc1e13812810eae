#include "slam/baselines/planar_scan.hpp"

#include <cmath>
#include <limits>

namespace isg::slam {

PlanarScan planarScan(const sensors::Scan& scan, const Eigen::Isometry3d& R_T_L,
                      const PlanarScanOptions& options) {
  PlanarScan out;
  const Eigen::Vector3d sensor = R_T_L.translation();
  out.origin = sensor.head<2>();
  const int bins = std::max(1, int(std::lround(360.0 / options.bearing_step_deg)));
  const double bin_width = 2.0 * M_PI / bins;
  std::vector<double> nearest(bins, std::numeric_limits<double>::infinity());
  std::vector<Eigen::Vector2d> points(bins);
  for (const auto& p : scan.points) {
    const Eigen::Vector3d q = R_T_L * Eigen::Vector3d(p.x, p.y, p.z);
    if (std::abs(q.z() - sensor.z()) > options.band) continue;
    const Eigen::Vector2d d = q.head<2>() - out.origin;
    const double range = d.norm();
    if (!(range >= options.min_range && range <= options.max_range)) continue;
    const int bin =
        std::min(bins - 1, int((std::atan2(d.y(), d.x()) + M_PI) / bin_width));  // [-π, π)
    if (range < nearest[bin]) {
      nearest[bin] = range;
      points[bin] = q.head<2>();
    }
  }
  for (int b = 0; b < bins; ++b) {
    if (!std::isfinite(nearest[b])) continue;
    out.endpoints.push_back(points[b]);
    out.ranges.push_back(nearest[b]);
  }
  return out;
}

}  // namespace isg::slam
