#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "slam/sgraph/voxel_index.hpp"

namespace isg::slam {

// The LiDAR odometry's local map (docs/slam.md, "Without odometry"): space cut into voxels, each
// holding the moments of the points in it (count, sum, sum of outer products) and, from them, the
// plane those points lie on. A keyframe's cloud enters as its contribution and leaves by
// subtracting the same contribution, so the map is updated, not rebuilt, as keyframes come and
// go; its size follows the space the recent keyframes saw, not the length of the run.
struct PlaneVoxelMapOptions {
  double voxel = 0.5;           // m
  int min_points = 5;           // fewer in a voxel: no plane
  double max_planarity = 0.05;  // smallest eigenvalue share: above, no plane (an edge, clutter)
  double min_spread = 0.1;      // middle eigenvalue share: below, a line (one ring), no plane
};

class PlaneVoxelMap {
 public:
  // A cloud's moments per voxel, in coordinates relative to the voxel's corner (small numbers,
  // so that adding and later subtracting them leaves no visible residue).
  struct Moments {
    int count = 0;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
  };
  struct Contribution {
    std::vector<std::pair<std::uint64_t, Moments>> voxels;  // by key, each key once
  };
  struct Voxel {
    std::uint64_t key = 0;
    Eigen::Vector3d corner = Eigen::Vector3d::Zero();  // in M
    Moments moments;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();    // in M
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // unit, or zero: not a plane
  };
  // A point's plane: the voxel whose plane lies nearest the point, and the signed distance.
  struct Match {
    const Voxel* voxel = nullptr;  // null: no plane within reach
    double residual = 0.0;         // n · (p − mean)
    bool occupied = false;         // the point's own voxel holds points (a plane or not)
  };

  explicit PlaneVoxelMap(const PlaneVoxelMapOptions& options = {});

  // The moments of `cloud` (points in L) placed at M_T_L.
  Contribution contributionOf(const std::vector<Eigen::Vector3f>& cloud,
                              const Eigen::Isometry3d& M_T_L) const;
  void add(const Contribution& contribution);
  // Takes back a contribution added before.
  void remove(const Contribution& contribution);

  bool empty() const { return live_ == 0; }
  // The voxel of `key` when it holds points, else null.
  const Voxel* voxel(std::uint64_t key) const {
    const int at = index_.find(key);
    return at >= 0 && voxels_[at].moments.count > 0 ? &voxels_[at] : nullptr;
  }
  // Voxels holding points.
  std::size_t size() const { return live_; }
  // The plane for p: its own voxel's when that is a plane within `max_distance` along its normal;
  // otherwise, of the 26 neighbours' planes within `max_distance` whose extent p lies across from
  // (within a voxel of the plane's mean along it), the one nearest p. Safe from several threads.
  Match match(const Eigen::Vector3d& p, double max_distance) const;

  // match() for many points against an unchanging map (a registration's passes): each cell's own
  // voxel and its neighbours' planes are looked up once and kept, so that the points of a cell,
  // and the same points again at the next pass, skip the 27 lookups. match() is a Lookup used
  // once. Valid while the map is not changed; one per thread.
  class Lookup {
   public:
    // `expected_cells`: how many cells it will likely meet (its index grows past that).
    explicit Lookup(const PlaneVoxelMap& map, std::size_t expected_cells = 1024)
        : map_(map), index_(expected_cells) {}
    Match match(const Eigen::Vector3d& p, double max_distance);

   private:
    struct Cell {
      const Voxel* own;  // the cell's voxel when it holds points, else null
      int first, last;   // its neighbours' planes: planes_[first, last)
    };
    const PlaneVoxelMap& map_;
    VoxelIndex index_;  // cell key → cells_
    std::vector<Cell> cells_;
    std::vector<const Voxel*> planes_;
  };

 private:
  Eigen::Vector3i cellOf(const Eigen::Vector3d& p) const;
  void update(Voxel& voxel) const;
  void compactIfSparse();

  PlaneVoxelMapOptions options_;
  std::vector<Voxel> voxels_;
  VoxelIndex index_;
  std::size_t live_ = 0;
};

}  // namespace isg::slam
