#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>

namespace isg::slam {

// Voxel keys: 21 bits per axis around the origin, so ±(2^20 · voxel) — 200 km at 0.2 m — without
// two cells sharing a key. Keys sort x, then y, z.

// floor(x) as an integer, for finite x within ±2^62: exactly std::floor's, inline. Built for the
// baseline x86-64 (no SSE4.1 round instruction) std::floor is a library call, and the odometry
// takes three per scan point.
inline std::int64_t floorToInt(double x) {
  const auto whole = std::int64_t(x);  // truncated towards zero
  return double(whole) > x ? whole - 1 : whole;
}

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
    return std::uint64_t(floorToInt(v / voxel) + (1 << 20)) & 0x1FFFFF;
  };
  return (axis(p.x()) << 42) | (axis(p.y()) << 21) | axis(p.z());
}

}  // namespace isg::slam
