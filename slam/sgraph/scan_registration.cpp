#include "slam/sgraph/scan_registration.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <nanoflann.hpp>
#include <numeric>

#include "slam/sgraph/plane_normal.hpp"
#include "slam/sgraph/voxel_index.hpp"
#include "slam/sgraph/voxel_key.hpp"

namespace isg::slam {

namespace {

// Points grouped by voxel: each voxel's key, and its points' sum (added in the order the points
// came) and count. A hash index finds the voxel, and only the voxels are sorted, by key — not
// every point, as a stable sort of (key, point) pairs did; the sums are the same bits, since each
// voxel's points are still added in their order.
struct VoxelCentroids {
  struct Voxel {
    std::uint64_t key;
    Eigen::Vector3d sum;
    int count;
  };
  double size;
  VoxelIndex index;
  std::vector<Voxel> voxels;

  VoxelCentroids(double voxel, std::size_t expected_points)
      : size(voxel), index(expected_points / 4 + 16) {}
  void add(const Eigen::Vector3d& p) {
    const std::uint64_t key = voxelKey(p, size);
    const int at = index.insert(key, int(voxels.size()));
    if (at == int(voxels.size())) voxels.push_back({key, Eigen::Vector3d::Zero(), 0});
    voxels[at].sum += p;
    ++voxels[at].count;
  }
  // One centroid per voxel, in key order.
  std::vector<Eigen::Vector3d> centroids() {
    std::sort(voxels.begin(), voxels.end(),
              [](const Voxel& a, const Voxel& b) { return a.key < b.key; });
    std::vector<Eigen::Vector3d> out;
    out.reserve(voxels.size());
    for (const Voxel& v : voxels) out.push_back(v.sum / double(v.count));
    return out;
  }
};

Eigen::Matrix2d rotation(double yaw) { return Eigen::Rotation2Dd(yaw).toRotationMatrix(); }

}  // namespace

std::vector<Eigen::Vector3f> downsampleScan(const sensors::Scan& scan,
                                            const ScanRegistrationOptions& options) {
  VoxelCentroids voxels(options.voxel, scan.points.size());
  for (const auto& p : scan.points) {
    const Eigen::Vector3d v(p.x, p.y, p.z);
    const double range = v.norm();
    if (!std::isfinite(range) || range < options.min_range || range > options.max_range) continue;
    voxels.add(v);
  }
  std::vector<Eigen::Vector3f> out;
  for (const auto& c : voxels.centroids()) out.push_back(c.cast<float>());
  return out;
}

struct LocalMap::Index {
  // nanoflann's view of the map's points.
  struct Cloud {
    const std::vector<Eigen::Vector3d>* points = nullptr;
    std::size_t kdtree_get_point_count() const { return points->size(); }
    double kdtree_get_pt(std::size_t i, std::size_t axis) const { return (*points)[i][int(axis)]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const {
      return false;
    }
  };
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>,
                                                   Cloud, 3, int>;
  Cloud cloud;
  std::unique_ptr<Tree> tree;
};

LocalMap::~LocalMap() = default;
LocalMap::LocalMap(LocalMap&& other) noexcept
    : points_(std::move(other.points_)),
      normals_(std::move(other.normals_)),
      normal_known_(std::move(other.normal_known_)),
      options_(other.options_),
      pool_(other.pool_),
      index_(std::move(other.index_)) {
  if (index_) index_->cloud.points = &points_;
}
LocalMap& LocalMap::operator=(LocalMap&& other) noexcept {
  points_ = std::move(other.points_);
  normals_ = std::move(other.normals_);
  normal_known_ = std::move(other.normal_known_);
  options_ = other.options_;
  pool_ = other.pool_;
  index_ = std::move(other.index_);
  if (index_) index_->cloud.points = &points_;
  return *this;
}

LocalMap::LocalMap(const std::vector<Part>& parts, const ScanRegistrationOptions& options,
                   ThreadPool* pool)
    : options_(options), pool_(pool), index_(std::make_unique<Index>()) {
  std::size_t expected = 0;
  for (const auto& part : parts) expected += part.cloud->size();
  VoxelCentroids voxels(options.voxel, expected);
  for (const auto& part : parts) {
    for (const auto& p : *part.cloud) voxels.add(part.M_T_L * p.cast<double>());
  }
  points_ = voxels.centroids();
  index_->cloud.points = &points_;
  if (points_.empty()) return;
  index_->tree = std::make_unique<Index::Tree>(3, index_->cloud,
                                               nanoflann::KDTreeSingleIndexAdaptorParams(10));
  normals_.assign(points_.size(), Eigen::Vector3d::Zero());
  normal_known_.assign(points_.size(), 0);
}

void LocalMap::computeNormal(std::size_t i, std::vector<int>& indices,
                             std::vector<double>& squared) const {
  // By PCA of the point's neighbourhood; none where it is not a plane.
  const int found = int(
      index_->tree->knnSearch(points_[i].data(), indices.size(), indices.data(), squared.data()));
  int used = 0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int k = 0; k < found; ++k) {
    if (squared[k] > options_.normal_radius * options_.normal_radius) break;
    mean += points_[indices[k]];
    ++used;
  }
  if (used < 5) return;
  mean /= double(used);
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (int k = 0; k < used; ++k) {
    const Eigen::Vector3d d = points_[indices[k]] - mean;
    covariance += d * d.transpose();
  }
  normals_[i] = planeNormalOf(covariance, options_.max_planarity, options_.min_spread);
}

void LocalMap::prepareNormals(const std::vector<int>& indices) const {
  wanted_.clear();
  for (const int i : indices) {
    if (i < 0 || normal_known_[i]) continue;
    normal_known_[i] = 1;
    wanted_.push_back(i);
  }
  if (wanted_.empty()) return;
  const int k_max = std::max(1, options_.normal_neighbours);
  // Each point's normal on its own: items of points on the pool's threads, if any.
  constexpr int kItem = 256;
  const int items = itemCount(int(wanted_.size()), kItem);
  const std::function<void(int)> item_normals = [&](int item) {
    std::vector<int> neighbours(k_max);
    std::vector<double> squared(k_max);
    const std::size_t end = std::min(wanted_.size(), std::size_t(item + 1) * kItem);
    for (std::size_t w = std::size_t(item) * kItem; w < end; ++w) {
      computeNormal(std::size_t(wanted_[w]), neighbours, squared);
    }
  };
  if (pool_ != nullptr && items > 1) {
    pool_->run(items, item_normals);
  } else {
    for (int i = 0; i < items; ++i) item_normals(i);
  }
}

int LocalMap::nearest(const Eigen::Vector3d& q, double max_distance, double* distance) const {
  if (points_.empty()) return -1;
  int index = -1;
  double squared = 0.0;
  nanoflann::KNNResultSet<double, int> result(1);
  result.init(&index, &squared);
  index_->tree->findNeighbors(result, q.data(), nanoflann::SearchParams());
  if (result.size() < 1 || squared > max_distance * max_distance) return -1;
  *distance = std::sqrt(squared);
  return index;
}

Eigen::Isometry3d planarCorrection(const Eigen::Vector3d& correction,
                                   const Eigen::Vector2d& pivot) {
  Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
  delta.linear() = Eigen::AngleAxisd(correction.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector2d t = pivot - rotation(correction.z()) * pivot + correction.head<2>();
  delta.translation() = Eigen::Vector3d(t.x(), t.y(), 0.0);
  return delta;
}

Eigen::Isometry3d RegistrationResult::apply(const Eigen::Isometry3d& M_T_R_predicted) const {
  return planarCorrection(correction, M_T_R_predicted.translation().head<2>()) * M_T_R_predicted;
}

namespace {

// The scan's points in M at the prediction, relative to the pivot in x and y, against the local
// map: the point-to-plane passes of the alignment and the share of points near the map. The
// points go in items of kItem, on the pool's threads when there is one; each item's sums are
// added in item order, so the result does not depend on the number of threads.
class ScanAlignment {
 public:
  static constexpr int kItem = 256;
  // A pass's sums: the Gauss-Newton system and the correspondences made.
  struct Sums {
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    int used = 0, near = 0;
  };

  ScanAlignment(const std::vector<Eigen::Vector3f>& scan_in_L, const Eigen::Isometry3d& M_T_L,
                const Eigen::Vector2d& pivot, const LocalMap& map,
                const ScanRegistrationOptions& options, ThreadPool* pool)
      : pivot_(pivot), map_(map), options_(options), pool_(pool) {
    points_.reserve(scan_in_L.size());
    for (const auto& p : scan_in_L) {
      Eigen::Vector3d q = M_T_L * p.cast<double>();
      q.head<2>() -= pivot;
      points_.push_back(q);
    }
    items_ = itemCount(int(points_.size()), kItem);
    sums_.resize(items_);
  }

  int points() const { return int(points_.size()); }

  // The share of points within the final tolerance of a map point at correction x.
  double shareWithin(const Eigen::Vector3d& x) {
    std::vector<int> near(items_, 0);
    forItems([&](int item) {
      const int end = std::min(int(points_.size()), (item + 1) * kItem);
      for (int i = item * kItem; i < end; ++i) {
        double d = 0.0;
        if (map_.nearest(transformed(x, points_[i]), options_.max_correspondence_end, &d) >= 0)
          ++near[item];
      }
    });
    return double(std::accumulate(near.begin(), near.end(), 0)) / double(points_.size());
  }

  // One pass at correction x: each point's nearest map point within max_distance, a robust
  // point-to-plane row where the map point has a wall's normal; `near` counts those within
  // near_distance. In three steps: the nearest map points, then the normals of those met for the
  // first time (each computed once per map point and registration), then the rows.
  Sums pass(const Eigen::Vector3d& x, double max_distance, double near_distance) {
    nearest_.resize(points_.size());
    distance_.resize(points_.size());
    forItems([&](int item) {
      const int end = std::min(int(points_.size()), (item + 1) * kItem);
      for (int i = item * kItem; i < end; ++i) {
        nearest_[i] = map_.nearest(transformed(x, points_[i]), max_distance, &distance_[i]);
      }
    });
    map_.prepareNormals(nearest_);
    forItems([&](int item) {
      Sums& s = sums_[item];
      s = Sums();
      const int end = std::min(int(points_.size()), (item + 1) * kItem);
      for (int i = item * kItem; i < end; ++i) {
        const int m = nearest_[i];
        if (m < 0) continue;
        const Eigen::Vector3d p = transformed(x, points_[i]);
        if (distance_[i] <= near_distance) ++s.near;
        const Eigen::Vector3d& n = map_.normal(m);
        if (n.isZero() || std::abs(n.z()) > options_.max_normal_z) continue;
        const double r = n.dot(p - map_.point(m));
        addPlanarRow(n, r, p.head<2>() - pivot_ - x.head<2>(), options_.huber, s.H, s.g);
        ++s.used;
      }
    });
    Sums total;
    for (const Sums& s : sums_) {
      total.H += s.H;
      total.g += s.g;
      total.used += s.used;
      total.near += s.near;
    }
    return total;
  }

 private:
  Eigen::Vector3d transformed(const Eigen::Vector3d& x, const Eigen::Vector3d& q) const {
    Eigen::Vector3d out = q;
    out.head<2>() = rotation(x.z()) * q.head<2>() + pivot_ + x.head<2>();
    return out;
  }
  void forItems(const std::function<void(int)>& task) {
    if (pool_ != nullptr) {
      pool_->run(items_, task);
    } else {
      for (int i = 0; i < items_; ++i) task(i);
    }
  }

  std::vector<Eigen::Vector3d> points_;
  Eigen::Vector2d pivot_;
  const LocalMap& map_;
  const ScanRegistrationOptions& options_;
  ThreadPool* pool_;
  int items_ = 0;
  std::vector<Sums> sums_;
  // A pass's nearest map point per scan point (−1: none within reach), and its distance.
  std::vector<int> nearest_;
  std::vector<double> distance_;
};

}  // namespace

RegistrationResult registerScan(const std::vector<Eigen::Vector3f>& scan_in_L,
                                const Eigen::Isometry3d& M_T_R_predicted,
                                const Eigen::Isometry3d& R_T_L, const LocalMap& map,
                                const Eigen::Matrix3d& prior_information,
                                const ScanRegistrationOptions& options, ThreadPool* pool) {
  RegistrationResult result;
  if (map.empty() || scan_in_L.empty()) return result;
  ScanAlignment alignment(scan_in_L, M_T_R_predicted * R_T_L,
                          M_T_R_predicted.translation().head<2>(), map, options, pool);
  result.points = alignment.points();
  const double sigma2 = options.point_sigma * options.point_sigma;
  // Each pass finds every point's nearest map point anyway: the shares come from those passes
  // (the first, at the prediction; the last at the final tolerance) rather than from passes of
  // their own.
  if (options.max_correspondence_start < options.max_correspondence_end) {
    result.inlier_share_predicted = alignment.shareWithin(Eigen::Vector3d::Zero());
  }
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  Eigen::Matrix3d scan_information = Eigen::Matrix3d::Zero();
  bool final_share_known = false;
  for (PassSchedule schedule(options); schedule.more();) {
    const double max_distance = schedule.maxDistance();
    const ScanAlignment::Sums sums = alignment.pass(x, max_distance, schedule.nearDistance());
    const double share = double(sums.near) / double(alignment.points());
    if (schedule.first() && max_distance >= options.max_correspondence_end) {
      result.inlier_share_predicted = share;
    }
    result.correspondences = sums.used;
    if (sums.used < 10) break;
    const double scale =
        options.effective_points / std::max(double(sums.used), options.effective_points);
    scan_information = sums.H * (scale / sigma2);
    const Eigen::Matrix3d total = scan_information + prior_information;
    const Eigen::Vector3d gradient = sums.g * (scale / sigma2) + prior_information * x;
    const Eigen::Vector3d step = -total.ldlt().solve(gradient);
    if (!step.allFinite()) break;
    x += step;
    if (schedule.finalStage()) {
      // At the final tolerance, after a step under a millimetre the share before it is the share
      // at x; after a larger one (the pass budget ran out first) it is counted again below.
      result.inlier_share = share;
      final_share_known = PassSchedule::settled(step.head<2>().norm(), step.z());
    }
    schedule.stepped(step.head<2>().norm(), step.z());
  }
  result.correction = x;
  result.information = scan_information;
  if (!final_share_known) result.inlier_share = alignment.shareWithin(x);
  result.agrees = result.inlier_share >= options.min_inlier_share;
  return result;
}

}  // namespace isg::slam
