#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <memory>
#include <vector>

#include "sensors/messages.hpp"
#include "slam/thread_pool.hpp"

namespace isg::slam {

// LiDAR odometry (docs/slam.md): each keyframe's scan registered to a local map made of the
// recent keyframes' scans, by point-to-plane ICP in the plane (x, y, yaw), fused with the leg
// odometry's prediction as a prior. Height, roll and pitch stay the odometry's (a legged base's
// IMU and leg kinematics observe them well); the walls constrain the planar pose.
struct ScanRegistrationOptions {
  bool enabled = true;
  double voxel = 0.2;  // m, scan and local-map points
  double min_range = 0.5, max_range = 30.0;
  int local_map_keyframes = 8;  // the latest keyframes' scans make the local map
  int normal_neighbours = 10;
  double normal_radius = 0.6;   // m, neighbours for a map point's normal
  double max_planarity = 0.05;  // smallest eigenvalue share: above, no normal (an edge, clutter)
  double min_spread = 0.1;      // middle eigenvalue share: below, a line (one ring), no normal
  double max_normal_z = 0.7;    // map normals steeper than this do not constrain (x, y, yaw)
  int iterations = 12;
  double max_correspondence_start = 0.8;  // m, shrinking linearly to ...
  double max_correspondence_end = 0.25;   // m
  double huber = 0.1;                     // m, on point-to-plane residuals
  double point_sigma = 0.05;              // m
  // Neighbouring scan points are not independent: the information of a registration is that of
  // this many points, however many there are (docs/slam.md).
  double effective_points = 60.0;
  // The scan-match factor enters the window with this share of the registration's information.
  // Consecutive registrations share most of their local map, so their errors are correlated, not
  // independent; at full weight the chain of them outweighed the plane observations and the plan
  // (APE on D1–D6 as built, docs/slam.md).
  double factor_information_share = 0.2;
  // Below this share of scan points within max_correspondence_end of the local map, the scan does
  // not agree with the recent map: no factor, and the localizer is told (a kidnap, a failure).
  double min_inlier_share = 0.25;
};

// The passes of a point-to-plane registration (registerScan, registerToPlanes): the
// correspondence tolerance shrinks stage by stage from max_correspondence_start to
// max_correspondence_end over `iterations` passes; once a step is under a millimetre (and
// 0.1 mrad) the estimate has settled at that tolerance and the passes left go to the final one,
// where a step under a tenth of that ends them.
class PassSchedule {
 public:
  explicit PassSchedule(const ScanRegistrationOptions& options)
      : options_(options), iterations_(std::max(1, options.iterations)) {}
  bool more() const { return pass_ < iterations_ && !done_; }
  bool first() const { return pass_ == 0; }
  bool finalStage() const { return stage_ == iterations_ - 1; }
  double maxDistance() const {
    const double fraction = iterations_ == 1 ? 1.0 : double(stage_) / double(iterations_ - 1);
    return options_.max_correspondence_start +
           fraction * (options_.max_correspondence_end - options_.max_correspondence_start);
  }
  // Correspondences this near count as the scan agreeing with the map.
  double nearDistance() const { return std::min(maxDistance(), options_.max_correspondence_end); }
  // A step under a millimetre (translation, m) and 0.1 mrad (yaw, rad).
  static bool settled(double translation, double yaw) {
    return translation < 1e-3 && std::abs(yaw) < 1e-4;
  }
  // After each pass's step.
  void stepped(double translation, double yaw) {
    if (finalStage()) {
      done_ = translation < 1e-4 && std::abs(yaw) < 1e-5;
    } else {
      stage_ = settled(translation, yaw) ? iterations_ - 1 : stage_ + 1;
    }
    ++pass_;
  }

 private:
  const ScanRegistrationOptions& options_;
  int iterations_;
  int pass_ = 0, stage_ = 0;
  bool done_ = false;
};

// One robust point-to-plane row of a planar registration on (dx, dy, dyaw) about a pivot: the
// residual r along the plane's normal n, for a point whose lever arm from the pivot is `arm`
// (d(point)/d(yaw) is the arm turned by 90°), Huber-weighted, added to the Gauss-Newton sums.
inline void addPlanarRow(const Eigen::Vector3d& n, double r, const Eigen::Vector2d& arm,
                         double huber, Eigen::Matrix3d& H, Eigen::Vector3d& g) {
  const Eigen::Vector3d J(n.x(), n.y(), n.x() * -arm.y() + n.y() * arm.x());
  const double w = std::abs(r) <= huber ? 1.0 : huber / std::abs(r);
  H += w * J * J.transpose();
  g += w * J * r;
}

// Voxel-grid centroids of a scan's points within the range limits, in the scan's frame; the same
// points give the same cloud (sorted by voxel).
std::vector<Eigen::Vector3f> downsampleScan(const sensors::Scan& scan,
                                            const ScanRegistrationOptions& options);

// The recent map: points in M with normals, searchable (a nanoflann k-d tree). Built from
// keyframe clouds and poses. A point's normal is computed when first asked for (prepareNormals):
// a registration meets a part of the map only, and the normal (a PCA of the point's
// neighbourhood, the costliest part of the map) of a point it never meets would be wasted. A
// normal does not depend on when it is computed, so the registration is the same.
class LocalMap {
 public:
  struct Part {
    const std::vector<Eigen::Vector3f>* cloud;  // in the keyframe's LiDAR frame
    Eigen::Isometry3d M_T_L;
  };
  // `pool`: threads for the normals (none: this thread); the map is the same either way.
  LocalMap(const std::vector<Part>& parts, const ScanRegistrationOptions& options,
           ThreadPool* pool = nullptr);
  ~LocalMap();
  LocalMap(LocalMap&&) noexcept;
  LocalMap& operator=(LocalMap&&) noexcept;

  bool empty() const { return points_.empty(); }
  std::size_t size() const { return points_.size(); }
  // The nearest map point to q: index, or -1 when none within max_distance. Safe to call from
  // several threads at once.
  int nearest(const Eigen::Vector3d& q, double max_distance, double* distance) const;
  const Eigen::Vector3d& point(int i) const { return points_[i]; }
  // Computes the normals of `indices` (map points, repeats allowed) not computed yet, on the
  // pool's threads if any. Not safe beside other calls on the same map; normal() afterwards is.
  void prepareNormals(const std::vector<int>& indices) const;
  // Unit normal, or zero where the neighbourhood is not planar; prepareNormals({i}) first (a
  // debug build stops here when it was not).
  const Eigen::Vector3d& normal(int i) const {
    assert(normal_known_[i] && "LocalMap::normal before prepareNormals");
    return normals_[i];
  }

 private:
  struct Index;
  void computeNormal(std::size_t i, std::vector<int>& indices, std::vector<double>& squared) const;
  std::vector<Eigen::Vector3d> points_;
  // Normals as they are asked for; normal_known_[i] says whether normals_[i] is computed.
  mutable std::vector<Eigen::Vector3d> normals_;
  mutable std::vector<char> normal_known_;
  mutable std::vector<int> wanted_;  // prepareNormals' scratch space
  ScanRegistrationOptions options_;
  ThreadPool* pool_ = nullptr;
  std::unique_ptr<Index> index_;
};

struct RegistrationResult {
  // The correction to the predicted pose: a rotation by yaw about the base's predicted position
  // and a translation, in M: M_T_R = Δ · M_T_R_predicted.
  Eigen::Vector3d correction = Eigen::Vector3d::Zero();  // dx, dy, dyaw
  // The scan's own information on (dx, dy, dyaw), prior excluded, scaled to effective_points.
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  double inlier_share = 0.0;            // after registration
  double inlier_share_predicted = 0.0;  // at the odometry's prediction
  int points = 0;                       // scan points used
  int correspondences = 0;              // at the last iteration
  bool agrees = false;                  // inlier_share ≥ min_inlier_share
  Eigen::Isometry3d apply(const Eigen::Isometry3d& M_T_R_predicted) const;
};

// Registers a scan (deskewed, downsampled, in L) predicted at M_T_R with the LiDAR at R_T_L,
// against the local map; `prior_information` (on dx, dy, dyaw) is the odometry's confidence in
// the prediction. `pool`: threads for the correspondences (none: this thread); the result is the
// same either way.
RegistrationResult registerScan(const std::vector<Eigen::Vector3f>& scan_in_L,
                                const Eigen::Isometry3d& M_T_R_predicted,
                                const Eigen::Isometry3d& R_T_L, const LocalMap& map,
                                const Eigen::Matrix3d& prior_information,
                                const ScanRegistrationOptions& options, ThreadPool* pool = nullptr);

// Δ for a planar correction (dx, dy, dyaw) about `pivot` (x, y in M).
Eigen::Isometry3d planarCorrection(const Eigen::Vector3d& correction, const Eigen::Vector2d& pivot);

}  // namespace isg::slam
