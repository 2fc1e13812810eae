#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>

namespace isg::slam {

// The key of the `voxel`-sized cell a point falls in: 21 bits per axis around the origin, so
// ±(2^20 · voxel) — 200 km at 0.2 m — without two cells sharing a key. Keys sort x, then y, z.
inline std::uint64_t voxelKey(const Eigen::Vector3d& p, double voxel) {
  auto axis = [voxel](double v) {
    return std::uint64_t(std::int64_t(std::floor(v / voxel)) + (1 << 20)) & 0x1FFFFF;
  };
  return (axis(p.x()) << 42) | (axis(p.y()) << 21) | axis(p.z());
}

}  // namespace isg::slam
