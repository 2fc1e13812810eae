#include "slam/sgraph/plane_voxel_map.hpp"

#include <cmath>

#include "slam/sgraph/plane_normal.hpp"
#include "slam/sgraph/voxel_key.hpp"

namespace isg::slam {

PlaneVoxelMap::PlaneVoxelMap(const PlaneVoxelMapOptions& options) : options_(options) {}

Eigen::Vector3i PlaneVoxelMap::cellOf(const Eigen::Vector3d& p) const {
  return Eigen::Vector3i(int(floorToInt(p.x() / options_.voxel)),
                         int(floorToInt(p.y() / options_.voxel)),
                         int(floorToInt(p.z() / options_.voxel)));
}

PlaneVoxelMap::Contribution PlaneVoxelMap::contributionOf(const std::vector<Eigen::Vector3f>& cloud,
                                                          const Eigen::Isometry3d& M_T_L) const {
  Contribution out;
  VoxelIndex index(cloud.size() / 4 + 16);
  for (const auto& point : cloud) {
    const Eigen::Vector3d p = M_T_L * point.cast<double>();
    const Eigen::Vector3i cell = cellOf(p);
    const std::uint64_t key = voxelKeyOfCell(cell);
    const int at = index.insert(key, int(out.voxels.size()));
    if (at == int(out.voxels.size())) out.voxels.push_back({key, Moments()});
    Moments& m = out.voxels[at].second;
    const Eigen::Vector3d local = p - cell.cast<double>() * options_.voxel;
    ++m.count;
    m.sum += local;
    m.outer += local * local.transpose();
  }
  return out;
}

void PlaneVoxelMap::update(Voxel& voxel) const {
  const Moments& m = voxel.moments;
  voxel.normal.setZero();
  if (m.count <= 0) return;
  const Eigen::Vector3d local_mean = m.sum / double(m.count);
  voxel.mean = voxel.corner + local_mean;
  if (m.count < options_.min_points) return;
  const Eigen::Matrix3d covariance =
      m.outer / double(m.count) - local_mean * local_mean.transpose();
  voxel.normal = planeNormalOf(covariance, options_.max_planarity, options_.min_spread);
}

void PlaneVoxelMap::add(const Contribution& contribution) {
  for (const auto& [key, moments] : contribution.voxels) {
    const int at = index_.insert(key, int(voxels_.size()));
    if (at == int(voxels_.size())) {
      Voxel voxel;
      voxel.key = key;
      voxel.corner = voxelCellOfKey(key).cast<double>() * options_.voxel;
      voxels_.push_back(voxel);
    }
    Voxel& voxel = voxels_[at];
    if (voxel.moments.count == 0) ++live_;
    voxel.moments.count += moments.count;
    voxel.moments.sum += moments.sum;
    voxel.moments.outer += moments.outer;
    update(voxel);
  }
}

void PlaneVoxelMap::remove(const Contribution& contribution) {
  for (const auto& [key, moments] : contribution.voxels) {
    const int at = index_.find(key);
    if (at < 0) continue;
    Voxel& voxel = voxels_[at];
    voxel.moments.count -= moments.count;
    if (voxel.moments.count <= 0) {
      // Emptied: exactly zero again, whatever rounding the sums left.
      voxel.moments = Moments();
      voxel.normal.setZero();
      --live_;
      continue;
    }
    voxel.moments.sum -= moments.sum;
    voxel.moments.outer -= moments.outer;
    update(voxel);
  }
  compactIfSparse();
}

void PlaneVoxelMap::compactIfSparse() {
  if (voxels_.size() <= 2 * live_ + 1024) return;
  std::vector<Voxel> kept;
  kept.reserve(live_);
  for (auto& voxel : voxels_) {
    if (voxel.moments.count > 0) kept.push_back(std::move(voxel));
  }
  voxels_ = std::move(kept);
  index_.clear(voxels_.size());
  for (std::size_t i = 0; i < voxels_.size(); ++i) index_.insert(voxels_[i].key, int(i));
}

PlaneVoxelMap::Match PlaneVoxelMap::match(const Eigen::Vector3d& p, double max_distance) const {
  return Lookup(*this, 1).match(p, max_distance);
}

PlaneVoxelMap::Match PlaneVoxelMap::Lookup::match(const Eigen::Vector3d& p, double max_distance) {
  const Eigen::Vector3i cell = map_.cellOf(p);
  const std::uint64_t key = voxelKeyOfCell(cell);
  const int at = index_.insert(key, int(cells_.size()));
  if (at == int(cells_.size())) {
    // First met: the cell's voxel, and its 26 neighbours' planes, dx then dy then dz from −1 to 1
    // (of planes equally near, the first in that order is the match).
    const Voxel* own = map_.voxel(key);
    const int first = int(planes_.size());
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
          if (dx == 0 && dy == 0 && dz == 0) continue;
          const int n = map_.index_.find(voxelKeyOfCell(cell + Eigen::Vector3i(dx, dy, dz)));
          if (n >= 0 && !map_.voxels_[n].normal.isZero()) planes_.push_back(&map_.voxels_[n]);
        }
      }
    }
    cells_.push_back({own, first, int(planes_.size())});
  }
  const Cell& c = cells_[at];
  Match out;
  if (c.own != nullptr) {
    out.occupied = true;
    if (!c.own->normal.isZero()) {
      const double r = c.own->normal.dot(p - c.own->mean);
      if (std::abs(r) <= max_distance) return {c.own, r, true};
    }
  }
  double best = max_distance;
  for (int i = c.first; i < c.last; ++i) {
    const Voxel& voxel = *planes_[i];
    const Eigen::Vector3d d = p - voxel.mean;
    const double r = voxel.normal.dot(d);
    if (std::abs(r) > best || (d - r * voxel.normal).norm() > map_.options_.voxel) continue;
    best = std::abs(r);
    out.voxel = &voxel;
    out.residual = r;
  }
  return out;
}

}  // namespace isg::slam
