#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "bim/plan.hpp"
#include "bim/plan_geometry.hpp"
#include "bim/polygon.hpp"
#include "common/occupancy_image.hpp"

namespace isg::raster::testing {

// A level drawn as a floor plan image is drawn: every wall's solid pieces (footprintPieces: its
// end extensions included, its door openings cut out) dark, the rest light; `margin` metres of
// light ground around the walls. `origin` receives the plan coordinates of the image's
// bottom-left corner.
inline common::OccupancyImage drawLevel(const bim::Level& level, double resolution, double margin,
                                        Eigen::Vector2d* origin) {
  const bim::LevelGeometry geometry = bim::computeLevelGeometry(level);
  std::vector<std::vector<Eigen::Vector2d>> pieces;
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const auto& wall : geometry.walls) {
    for (auto& piece : wall.footprintPieces()) {
      for (const auto& p : piece) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
      pieces.push_back(std::move(piece));
    }
  }
  lo -= Eigen::Vector2d::Constant(margin);
  hi += Eigen::Vector2d::Constant(margin);
  *origin = lo;
  common::OccupancyImage image;
  image.width = int(std::ceil((hi.x() - lo.x()) / resolution));
  image.height = int(std::ceil((hi.y() - lo.y()) / resolution));
  image.pixels.assign(std::size_t(image.width) * image.height, common::PixelClass::kFree);
  for (const auto& piece : pieces) {
    Eigen::Vector2d a(1e300, 1e300), b(-1e300, -1e300);
    for (const auto& p : piece) a = a.cwiseMin(p), b = b.cwiseMax(p);
    const int c0 = std::max(0, int((a.x() - lo.x()) / resolution) - 1);
    const int c1 = std::min(image.width - 1, int((b.x() - lo.x()) / resolution) + 1);
    const int u0 = std::max(0, int((a.y() - lo.y()) / resolution) - 1);
    const int u1 = std::min(image.height - 1, int((b.y() - lo.y()) / resolution) + 1);
    for (int u = u0; u <= u1; ++u) {
      for (int c = c0; c <= c1; ++c) {
        const Eigen::Vector2d centre = lo + resolution * Eigen::Vector2d(c + 0.5, u + 0.5);
        if (bim::containsPoint(piece, centre)) {
          image.pixels[std::size_t(image.height - 1 - u) * image.width + c] =
              common::PixelClass::kOccupied;
        }
      }
    }
  }
  return image;
}

}  // namespace isg::raster::testing
