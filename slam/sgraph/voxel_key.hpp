#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>

namespace isg::slam {

// Voxel keys: 21 bits per axis around the origin, so ±(2^20 · voxel) — 200 km at 0.2 m — without
// two cells sharing a key. Keys sort x, then y, z.

// The key of an integer cell (cell = floor(p / voxel) per axis).
inline std::uint64_t voxelKeyOfCell(const Eigen::Vector3i& cell) {
  auto axis = [](int v) { return std::uint64_t(std::int64_t(v) + (1 << 20)) & 0x1FFFFF; };
  return (axis(cell.x()) << 42) | (axis(cell.y()) << 21) | axis(cell.z());
}

// The cell back from its key: each axis's 21 bits less the offset.
inline Eigen::Vector3i voxelCellOfKey(std::uint64_t key) {
  auto axis = [key](int shift) { return int((key >> shift) & 0x1FFFFF) - (1 << 20); };
  return Eigen::Vector3i(axis(42), axis(21), axis(0));
}

// The key of the `voxel`-sized cell a point falls in.
inline std::uint64_t voxelKey(const Eigen::Vector3d& p, double voxel) {
  auto axis = [voxel](double v) {
    return std::uint64_t(std::int64_t(std::floor(v / voxel)) + (1 << 20)) & 0x1FFFFF;
  };
  return (axis(p.x()) << 42) | (axis(p.y()) << 21) | axis(p.z());
}

}  // namespace isg::slam
