#pragma once

#include <cstdint>
#include <vector>

#include "common/occupancy_image.hpp"

namespace isg::raster {

using common::OccupancyImage;

// The skeleton of one region of occupied pixels (Zhang–Suen thinning), cut into its branches.
// A junction is a skeleton pixel where three or more branches meet (three or more neighbours and
// as many separate runs of them around it); neighbouring junction pixels are one junction. Each
// branch (chain) runs between junctions or free ends, its pixels in order; a closed loop without
// a junction is given one of its own, met by both its ends.
struct SkeletonChain {
  std::vector<std::uint32_t> pixels;    // indices into the image's pixels, in order along it
  int node_front = -1, node_back = -1;  // the junction each end meets, −1 at a free end
};

struct Skeleton {
  std::vector<SkeletonChain> chains;
  int junctions = 0;   // junction ids are 0 … junctions − 1
  int iterations = 0;  // thinning passes: about half the region's largest thickness in pixels
};

// `pixels`: the region's pixels (indices into image.pixels); the box: its columns and rows.
Skeleton thinRegion(const OccupancyImage& image, const std::vector<std::uint32_t>& pixels,
                    int min_column, int max_column, int min_row, int max_row);

}  // namespace isg::raster
