#pragma once

#include <cstdint>
#include <utility>
#include <vector>

namespace isg::slam {

// Voxel key (slam/sgraph/voxel_key.hpp) → an index into the caller's voxels: open addressing with
// linear probing in one flat array. The odometry looks voxels up several times per scan point and
// pass; std::unordered_map's node per entry and its pointer chase made that the bulk of the work.
// Entries are never erased one by one: a caller that lets voxels empty out rebuilds the index
// (clear, then insert the live ones) when the dead outnumber the living.
class VoxelIndex {
 public:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t(0);  // no voxel key has all 64 bits set

  explicit VoxelIndex(std::size_t expected = 1024) { reserveFor(expected); }

  // The index stored for `key`, or -1.
  int find(std::uint64_t key) const {
    for (std::size_t slot = slotOf(key);; slot = (slot + 1) & mask_) {
      const auto& [k, index] = slots_[slot];
      if (k == key) return index;
      if (k == kEmpty) return -1;
    }
  }

  // The index stored for `key`; `index` stored first when the key is new.
  int insert(std::uint64_t key, int index) {
    if ((size_ + 1) * 2 > slots_.size()) grow();
    for (std::size_t slot = slotOf(key);; slot = (slot + 1) & mask_) {
      auto& entry = slots_[slot];
      if (entry.first == key) return entry.second;
      if (entry.first == kEmpty) {
        entry = {key, index};
        ++size_;
        return index;
      }
    }
  }

  std::size_t size() const { return size_; }

  void clear(std::size_t expected) {
    slots_.clear();
    size_ = 0;
    reserveFor(expected);
  }

 private:
  void reserveFor(std::size_t expected) {
    std::size_t capacity = 16;
    shift_ = 60;
    while (capacity < expected * 2) capacity *= 2, --shift_;
    slots_.assign(capacity, {kEmpty, -1});
    mask_ = capacity - 1;
  }
  void grow() {
    std::vector<std::pair<std::uint64_t, int>> old = std::move(slots_);
    reserveFor(old.size());
    size_ = 0;
    for (const auto& [key, index] : old) {
      if (key != kEmpty) insert(key, index);
    }
  }
  std::size_t slotOf(std::uint64_t key) const {
    // Fibonacci hashing: the product's top bits, so that neighbouring keys (neighbouring voxels)
    // spread over the table.
    return std::size_t((key * 0x9E3779B97F4A7C15ull) >> shift_);
  }

  std::vector<std::pair<std::uint64_t, int>> slots_;
  std::size_t mask_ = 0;
  int shift_ = 60;
  std::size_t size_ = 0;
};

}  // namespace isg::slam
