#include "raster/raster_skeleton.hpp"

#include <array>
#include <unordered_map>

namespace isg::raster {
namespace {

// A local bitmap of the region's box with a one-pixel frame; bit 0: on, bit 1: listed.
struct Bitmap {
  int width, height, min_c, min_r, image_width;
  std::vector<std::uint8_t> bits;
  int local(std::uint32_t index) const {
    const int c = int(index % image_width) - min_c + 1, r = int(index / image_width) - min_r + 1;
    return r * width + c;
  }
  std::uint32_t global(int i) const {
    const int c = i % width - 1 + min_c, r = i / width - 1 + min_r;
    return std::uint32_t(r) * image_width + c;
  }
  bool on(int i) const { return bits[i] & 1; }
};

// The eight neighbours clockwise from north (rows grow downwards): P2 … P9 of Zhang–Suen.
std::array<int, 8> ring(int width) {
  return {-width, -width + 1, 1, width + 1, width, width - 1, -1, -width - 1};
}

int onNeighbours(const Bitmap& map, int i, const std::array<int, 8>& around) {
  int count = 0;
  for (int k = 0; k < 8; ++k) count += map.on(i + around[k]);
  return count;
}

// Runs of on pixels around i (off → on transitions on the closed ring).
int runsAround(const Bitmap& map, int i, const std::array<int, 8>& around) {
  int runs = 0;
  for (int k = 0; k < 8; ++k) runs += !map.on(i + around[k]) && map.on(i + around[(k + 1) % 8]);
  return runs;
}

bool removable(const Bitmap& map, int i, int sub, const std::array<int, 8>& around) {
  const int b = onNeighbours(map, i, around);
  // At least three neighbours (Lü and Wang's change to Zhang–Suen): with two, the end of a
  // diagonal line two pixels thick was removed pass after pass until the line was gone.
  if (b < 3 || b > 6 || runsAround(map, i, around) != 1) return false;
  const bool p2 = map.on(i + around[0]), p4 = map.on(i + around[2]), p6 = map.on(i + around[4]),
             p8 = map.on(i + around[6]);
  if (sub == 0) return !(p2 && p4 && p6) && !(p4 && p6 && p8);
  return !(p2 && p4 && p8) && !(p2 && p6 && p8);
}

// Thinning: only pixels on the region's border can go, so only they are listed. Returns the
// passes that removed pixels; bit 1 is clear again afterwards.
int thin(Bitmap& map, const std::vector<std::uint32_t>& pixels, const std::array<int, 8>& around) {
  std::vector<int> border, next, removed;
  for (auto index : pixels) {
    const int i = map.local(index);
    if (onNeighbours(map, i, around) < 8) {
      map.bits[i] |= 2;
      border.push_back(i);
    }
  }
  int iterations = 0;
  for (bool changed = true; changed;) {
    changed = false;
    for (int sub = 0; sub < 2; ++sub) {
      removed.clear();
      for (int i : border) {
        if (map.on(i) && removable(map, i, sub, around)) removed.push_back(i);
      }
      for (int i : removed) map.bits[i] &= ~1;
      changed = changed || !removed.empty();
      next.clear();
      for (int i : border) {
        if (map.on(i)) {
          next.push_back(i);
        } else {
          map.bits[i] &= ~2;
        }
      }
      for (int i : removed) {
        for (int k = 0; k < 8; ++k) {
          const int j = i + around[k];
          if (map.on(j) && !(map.bits[j] & 2)) {
            map.bits[j] |= 2;
            next.push_back(j);
          }
        }
      }
      border.swap(next);
    }
    if (changed) ++iterations;
  }
  for (int& i : border) map.bits[i] &= ~2;
  return iterations;
}

// Junction pixels (bit 2) and their clusters, numbered from skeleton.junctions on (ids in a map:
// one byte a pixel of the box is all that is held for the whole box). A junction pixel takes the
// skeleton pixels beside it: branches of an 8-connected skeleton touch each other diagonally next
// to the pixel where they meet, and a walk along one would slip into the other past it.
std::unordered_map<int, int> markJunctions(Bitmap& map, const std::vector<int>& skeleton_pixels,
                                           const std::array<int, 8>& around, Skeleton& skeleton) {
  std::vector<int> junction_pixels;
  for (int i : skeleton_pixels) {
    if (onNeighbours(map, i, around) >= 3 && runsAround(map, i, around) >= 3) {
      junction_pixels.push_back(i);
    }
  }
  const std::size_t centres = junction_pixels.size();
  for (std::size_t k = 0; k < centres; ++k) {
    for (int d = 0; d < 8; ++d) {
      const int q = junction_pixels[k] + around[d];
      if (map.on(q)) junction_pixels.push_back(q);
    }
  }
  for (int i : junction_pixels) map.bits[i] |= 4;
  std::unordered_map<int, int> junction_of;
  std::vector<int> stack;
  for (int i : junction_pixels) {
    if (junction_of.count(i)) continue;
    const int id = skeleton.junctions++;
    junction_of[i] = id;
    stack.assign(1, i);
    while (!stack.empty()) {
      const int p = stack.back();
      stack.pop_back();
      for (int k = 0; k < 8; ++k) {
        const int q = p + around[k];
        if ((map.bits[q] & 4) && !junction_of.count(q)) junction_of[q] = id, stack.push_back(q);
      }
    }
  }
  return junction_of;
}

// Branches: walks over the skeleton's pixels that are no junction's (bit 3: walked).
class BranchWalker {
 public:
  BranchWalker(Bitmap& map, const std::array<int, 8>& around,
               const std::unordered_map<int, int>& junction_of)
      : map_(map), around_(around), junction_of_(junction_of) {}

  bool isBranch(int q) const { return (map_.bits[q] & (1 | 4 | 8)) == 1; }

  // Along unwalked branch pixels from `from`, the four side neighbours first, appending to out.
  void walk(int from, std::vector<int>& out) {
    int current = from;
    for (;;) {
      int step = -1;
      for (int k = 0; k < 8 && step < 0; k += 2) {
        if (isBranch(current + around_[k])) step = current + around_[k];
      }
      for (int k = 1; k < 8 && step < 0; k += 2) {
        if (isBranch(current + around_[k])) step = current + around_[k];
      }
      if (step < 0) return;
      map_.bits[step] |= 8;
      out.push_back(step);
      current = step;
    }
  }

  int junctionBeside(int i) const {
    for (int k = 0; k < 8; ++k) {
      if (map_.bits[i + around_[k]] & 4) return junction_of_.at(i + around_[k]);
    }
    return -1;
  }

  bool adjacent(int a, int b) const {
    for (int k = 0; k < 8; ++k) {
      if (a + around_[k] == b) return true;
    }
    return false;
  }

  int branchNeighbours(int i) const {
    int count = 0;
    for (int k = 0; k < 8; ++k) count += (map_.bits[i + around_[k]] & (1 | 4)) == 1;
    return count;
  }

  // The branch through i, walked both ways from it.
  SkeletonChain chainThrough(int i, Skeleton& skeleton) {
    map_.bits[i] |= 8;
    std::vector<int> forward{i}, backward;
    walk(i, forward);
    walk(i, backward);
    std::vector<int> chain(backward.rbegin(), backward.rend());
    chain.insert(chain.end(), forward.begin(), forward.end());
    SkeletonChain out;
    out.node_front = junctionBeside(chain.front());
    out.node_back = junctionBeside(chain.back());
    if (out.node_front < 0 && out.node_back < 0 && chain.size() > 3 &&
        adjacent(chain.front(), chain.back())) {
      out.node_front = out.node_back = skeleton.junctions++;  // a closed loop
    }
    out.pixels.reserve(chain.size());
    for (int p : chain) out.pixels.push_back(map_.global(p));
    return out;
  }

 private:
  Bitmap& map_;
  const std::array<int, 8>& around_;
  const std::unordered_map<int, int>& junction_of_;
};

}  // namespace

Skeleton thinRegion(const OccupancyImage& image, const std::vector<std::uint32_t>& pixels,
                    int min_column, int max_column, int min_row, int max_row) {
  Bitmap map{
      max_column - min_column + 3, max_row - min_row + 3, min_column, min_row, image.width, {}};
  map.bits.assign(std::size_t(map.width) * map.height, 0);
  for (auto index : pixels) map.bits[map.local(index)] = 1;
  const auto around = ring(map.width);
  Skeleton skeleton;
  skeleton.iterations = thin(map, pixels, around);
  std::vector<int> skeleton_pixels;
  for (auto index : pixels) {
    const int i = map.local(index);
    if (map.on(i)) skeleton_pixels.push_back(i);
  }
  const std::unordered_map<int, int> junction_of =
      markJunctions(map, skeleton_pixels, around, skeleton);
  BranchWalker walker(map, around, junction_of);
  // Ends first (so that open branches are walked from an end), then whatever is left (loops).
  for (int pass = 0; pass < 2; ++pass) {
    for (int i : skeleton_pixels) {
      if ((map.bits[i] & (4 | 8)) != 0) continue;
      if (pass == 0 && walker.branchNeighbours(i) > 1) continue;
      skeleton.chains.push_back(walker.chainThrough(i, skeleton));
    }
  }
  return skeleton;
}

}  // namespace isg::raster
