#include "slam/sgraph/odometry_registration.hpp"

#include <algorithm>
#include <cmath>

namespace isg::slam {

namespace {

// The Gauss-Newton sums of one pass, and the points near the map.
struct PassSums {
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  int used = 0, near = 0;
};

// The scan's points at the prediction, x and y relative to the pivot (the base's predicted
// position), so that a correction's yaw turns about the base.
class PlaneAlignment {
 public:
  PlaneAlignment(const std::vector<Eigen::Vector3f>& scan_in_L, const Eigen::Isometry3d& M_T_L,
                 const Eigen::Vector2d& pivot, const PlaneVoxelMap& map,
                 const ScanRegistrationOptions& options)
      : pivot_(pivot), lookup_(map), options_(options) {
    points_.reserve(scan_in_L.size());
    for (const auto& p : scan_in_L) {
      Eigen::Vector3d q = M_T_L * p.cast<double>();
      q.head<2>() -= pivot;
      points_.push_back(q);
    }
  }
  int points() const { return int(points_.size()); }

  // One pass at correction x: each point's plane within max_distance, a robust point-to-plane row
  // where it is a wall's; `near` counts the points within near_distance of a plane or in a voxel
  // that holds points.
  PassSums pass(const Eigen::Vector3d& x, double max_distance, double near_distance) {
    PassSums s;
    const Eigen::Matrix2d turn = Eigen::Rotation2Dd(x(2)).toRotationMatrix();
    for (const auto& q : points_) {
      Eigen::Vector3d p = q;
      p.head<2>() = turn * q.head<2>() + pivot_ + x.head<2>();
      const PlaneVoxelMap::Match match = lookup_.match(p, max_distance);
      if (match.occupied || (match.voxel != nullptr && std::abs(match.residual) <= near_distance)) {
        ++s.near;
      }
      if (match.voxel == nullptr) continue;
      const Eigen::Vector3d& n = match.voxel->normal;
      if (std::abs(n.z()) > options_.max_normal_z) continue;  // not a wall: it holds the height
      addPlanarRow(n, match.residual, p.head<2>() - pivot_ - x.head<2>(), options_.huber, s.H, s.g);
      ++s.used;
    }
    return s;
  }

 private:
  std::vector<Eigen::Vector3d> points_;
  Eigen::Vector2d pivot_;
  // The map's planes near each cell the points fall in, kept over the passes: the points move by
  // centimetres from pass to pass, and mostly stay in their cells.
  PlaneVoxelMap::Lookup lookup_;
  const ScanRegistrationOptions& options_;
};

}  // namespace

RegistrationResult registerToPlanes(const std::vector<Eigen::Vector3f>& scan_in_L,
                                    const Eigen::Isometry3d& M_T_R_predicted,
                                    const Eigen::Isometry3d& R_T_L, const PlaneVoxelMap& map,
                                    const Eigen::Matrix3d& prior_information,
                                    const ScanRegistrationOptions& options) {
  RegistrationResult result;
  if (map.empty() || scan_in_L.empty()) return result;
  PlaneAlignment alignment(scan_in_L, M_T_R_predicted * R_T_L,
                           M_T_R_predicted.translation().head<2>(), map, options);
  result.points = alignment.points();
  const double sigma2 = options.point_sigma * options.point_sigma;
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  // The passes as in the S-Graph's registration. The share near the map is the final tolerance's
  // pass's before its last step (counted again below when that step was a millimetre or more).
  bool share_known = false;
  for (PassSchedule schedule(options); schedule.more();) {
    const PassSums sums = alignment.pass(x, schedule.maxDistance(), schedule.nearDistance());
    result.correspondences = sums.used;
    if (sums.used < 10) break;
    const double scale =
        options.effective_points / std::max(double(sums.used), options.effective_points);
    result.information = sums.H * (scale / sigma2);
    const Eigen::Matrix3d total = result.information + prior_information;
    const Eigen::Vector3d gradient = sums.g * (scale / sigma2) + prior_information * x;
    const Eigen::Vector3d step = -total.ldlt().solve(gradient);
    if (!step.allFinite()) break;
    x += step;
    if (schedule.finalStage()) {
      result.inlier_share = double(sums.near) / double(alignment.points());
      share_known = PassSchedule::settled(step.head<2>().norm(), step.z());
    }
    schedule.stepped(step.head<2>().norm(), step.z());
  }
  if (!share_known) {
    const double end = options.max_correspondence_end;
    result.inlier_share = double(alignment.pass(x, end, end).near) / double(alignment.points());
  }
  result.correction = x;
  result.agrees = result.inlier_share >= options.min_inlier_share;
  return result;
}

LevelOffset levelOffset(const std::vector<Eigen::Vector3f>& scan_in_L,
                        const Eigen::Isometry3d& M_T_L, const PlaneVoxelMap& map,
                        double max_distance, double huber, double min_normal_z) {
  LevelOffset out;
  PlaneVoxelMap::Lookup lookup(map);
  std::vector<double> heights;  // of the points above their planes, at this pass
  for (int pass = 0; pass < 3; ++pass) {
    heights.clear();
    double sum = 0.0, weights = 0.0;
    for (const auto& point : scan_in_L) {
      Eigen::Vector3d p = M_T_L * point.cast<double>();
      p.z() -= out.offset;
      const PlaneVoxelMap::Match match = lookup.match(p, max_distance);
      if (match.voxel == nullptr || std::abs(match.voxel->normal.z()) < min_normal_z) continue;
      const double above = match.residual / match.voxel->normal.z();  // along z, not n
      const double w = std::abs(above) <= huber ? 1.0 : huber / std::abs(above);
      sum += w * above;
      weights += w;
      heights.push_back(above);
    }
    out.points = int(heights.size());
    if (heights.empty()) break;
    const double mean = sum / weights;
    // The spread as the median absolute deviation (scaled to a normal's σ): a few points on the
    // wrong plane (a wall's foot, a box's edge) do not widen it.
    for (double& h : heights) h = std::abs(h - mean);
    const auto middle = heights.begin() + heights.size() / 2;
    std::nth_element(heights.begin(), middle, heights.end());
    out.spread = 1.4826 * *middle;
    out.offset += mean;
  }
  return out;
}

}  // namespace isg::slam
