#include "bim/free_space_rooms.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <map>

#include "bim/column.hpp"
#include "bim/plan_geometry.hpp"

namespace isg::bim {

namespace {

// The grid of the level's walls: occupied cells, and each free cell's region (0 outside).
struct Grid {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double cell = 0.05;
  int width = 0, height = 0;
  std::vector<std::uint8_t> occupied;
  std::vector<int> region;  // -1 occupied, 0 outside, k ≥ 1 the k-th enclosed region

  long index(int i, int j) const { return long(j) * width + i; }
  bool inside(int i, int j) const { return i >= 0 && j >= 0 && i < width && j < height; }
};

Grid drawWalls(const Level& level, const FreeSpaceOptions& options) {
  Grid grid;
  std::vector<Polygon2> footprints;
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300), hi = -lo;
  for (const auto& wall : computeLevelGeometry(level).walls) {
    footprints.push_back(wall.footprint());
    for (const auto& p : footprints.back()) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  for (const auto& column : level.columns) {  // rectangular ones are among the walls already
    if (!column.round()) continue;
    footprints.push_back(columnFootprint(column));
    for (const auto& p : footprints.back()) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  if (footprints.empty()) return grid;
  const Eigen::Vector2d size = hi - lo;
  grid.cell = std::max(options.cell, std::sqrt(size.x() * size.y() / double(options.max_cells)));
  // Two free cells all round: the outside reaches every side.
  grid.origin = lo - Eigen::Vector2d::Constant(2 * grid.cell);
  grid.width = int(std::ceil(size.x() / grid.cell)) + 4;
  grid.height = int(std::ceil(size.y() / grid.cell)) + 4;
  grid.occupied.assign(std::size_t(grid.width) * std::size_t(grid.height), 0);
  for (const auto& footprint : footprints) {
    Eigen::Vector2d f_lo = Eigen::Vector2d::Constant(1e300), f_hi = -f_lo;
    for (const auto& p : footprint) f_lo = f_lo.cwiseMin(p), f_hi = f_hi.cwiseMax(p);
    const int i0 = std::max(0, int(std::floor((f_lo.x() - grid.origin.x()) / grid.cell)));
    const int j0 = std::max(0, int(std::floor((f_lo.y() - grid.origin.y()) / grid.cell)));
    const int i1 =
        std::min(grid.width - 1, int(std::ceil((f_hi.x() - grid.origin.x()) / grid.cell)));
    const int j1 =
        std::min(grid.height - 1, int(std::ceil((f_hi.y() - grid.origin.y()) / grid.cell)));
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        const Eigen::Vector2d centre = grid.origin + grid.cell * Eigen::Vector2d(i + 0.5, j + 0.5);
        if (containsPoint(footprint, centre)) grid.occupied[std::size_t(grid.index(i, j))] = 1;
      }
    }
  }
  return grid;
}

// Labels the free cells: 0 for those connected to the border (outside), 1, 2, … for each
// enclosed region (4-connected), in row-major order of their first cell. Returns the count.
int labelRegions(Grid& grid) {
  grid.region.assign(grid.occupied.size(), -2);  // -2: free, not yet labelled
  for (std::size_t k = 0; k < grid.occupied.size(); ++k) {
    if (grid.occupied[k]) grid.region[k] = -1;
  }
  std::deque<std::pair<int, int>> queue;
  const auto fill = [&](int i0, int j0, int label) {
    grid.region[std::size_t(grid.index(i0, j0))] = label;
    queue.push_back({i0, j0});
    while (!queue.empty()) {
      const auto [i, j] = queue.front();
      queue.pop_front();
      for (const auto& [di, dj] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
        const int a = i + di, b = j + dj;
        if (!grid.inside(a, b) || grid.region[std::size_t(grid.index(a, b))] != -2) continue;
        grid.region[std::size_t(grid.index(a, b))] = label;
        queue.push_back({a, b});
      }
    }
  };
  fill(0, 0, 0);  // the border is free by construction, and all of it connected
  int regions = 0;
  for (int j = 0; j < grid.height; ++j) {
    for (int i = 0; i < grid.width; ++i) {
      if (grid.region[std::size_t(grid.index(i, j))] == -2) fill(i, j, ++regions);
    }
  }
  return regions;
}

using Vertex = std::pair<int, int>;  // a cell corner, in cells

// An enclosed region's cells: how many, and the box of cells that holds them.
struct RegionExtent {
  long cells = 0;
  int i0 = 1 << 30, j0 = 1 << 30, i1 = -1, j1 = -1;
};

// The region's boundary loops along cell edges, each counter-clockwise about the region (the
// region on the left): its outer boundary has positive area, its holes negative. Only the
// region's box is read: every region costs its own size, not the grid's.
std::vector<std::vector<Vertex>> boundaryLoops(const Grid& grid, int label,
                                               const RegionExtent& box) {
  const auto in = [&](int i, int j) {
    return grid.inside(i, j) && grid.region[std::size_t(grid.index(i, j))] == label;
  };
  std::multimap<Vertex, Vertex> edges;  // from → to
  for (int j = box.j0; j <= box.j1; ++j) {
    for (int i = box.i0; i <= box.i1; ++i) {
      if (!in(i, j)) continue;
      if (!in(i, j - 1)) edges.insert({{i, j}, {i + 1, j}});
      if (!in(i + 1, j)) edges.insert({{i + 1, j}, {i + 1, j + 1}});
      if (!in(i, j + 1)) edges.insert({{i + 1, j + 1}, {i, j + 1}});
      if (!in(i - 1, j)) edges.insert({{i, j + 1}, {i, j}});
    }
  }
  std::vector<std::vector<Vertex>> loops;
  while (!edges.empty()) {
    std::vector<Vertex> loop;
    auto edge = edges.begin();
    const Vertex first = edge->first;
    Vertex from = edge->first, to = edge->second;
    edges.erase(edge);
    loop.push_back(from);
    while (to != first) {
      loop.push_back(to);
      // Where two cells touch only at a corner, two edges leave it: the left turn keeps to the
      // cell the loop came along, so a loop never passes through one corner twice.
      const auto [begin, end] = edges.equal_range(to);
      if (begin == end) break;  // cannot happen on a closed boundary; guards the loop
      auto next = begin;
      const int dx = to.first - from.first, dy = to.second - from.second;
      for (auto it = begin; it != end; ++it) {
        const int ex = it->second.first - to.first, ey = it->second.second - to.second;
        if (dx * ey - dy * ex > 0) next = it;  // a left turn
      }
      from = to;
      to = next->second;
      edges.erase(next);
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

// Douglas–Peucker on the open chain points[first..last]: the indices kept.
void simplifyChain(const std::vector<Eigen::Vector2d>& points, std::size_t first, std::size_t last,
                   double tolerance, std::vector<bool>& keep) {
  if (last <= first + 1) return;
  double farthest = -1.0;
  std::size_t at = first;
  for (std::size_t k = first + 1; k < last; ++k) {
    const double d = distanceToSegment(points[k], points[first], points[last]);
    if (d > farthest) farthest = d, at = k;
  }
  if (farthest <= tolerance) return;
  keep[at] = true;
  simplifyChain(points, first, at, tolerance, keep);
  simplifyChain(points, at, last, tolerance, keep);
}

// The closed loop with its staircases straightened within `tolerance`: split at its two
// farthest-apart vertices, each half simplified. The loop itself when that would not be simple.
Polygon2 straightened(const Polygon2& loop, double tolerance) {
  const std::size_t n = loop.size();
  std::size_t far = 0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((loop[k] - loop[0]).squaredNorm() > (loop[far] - loop[0]).squaredNorm()) far = k;
  }
  std::vector<Eigen::Vector2d> chain(loop.begin(), loop.end());
  chain.push_back(loop[0]);
  std::vector<bool> keep(chain.size(), false);
  keep[0] = keep[far] = keep[n] = true;
  simplifyChain(chain, 0, far, tolerance, keep);
  simplifyChain(chain, far, n, tolerance, keep);
  Polygon2 out;
  for (std::size_t k = 0; k < n; ++k) {
    if (keep[k]) out.push_back(loop[k]);
  }
  if (out.size() < 3 || findSelfIntersection(out) || signedArea(out) <= 0) return loop;
  return out;
}

// The loop's corners only (collinear vertices removed), in metres.
Polygon2 cornersInMetres(const Grid& grid, const std::vector<Vertex>& loop) {
  Polygon2 out;
  const std::size_t n = loop.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Vertex& prev = loop[(k + n - 1) % n];
    const Vertex& here = loop[k];
    const Vertex& next = loop[(k + 1) % n];
    const long cross = long(here.first - prev.first) * (next.second - here.second) -
                       long(here.second - prev.second) * (next.first - here.first);
    if (cross == 0) continue;
    out.push_back(grid.origin + grid.cell * Eigen::Vector2d(here.first, here.second));
  }
  return out;
}

}  // namespace

FreeSpaceRooms enclosedFreeSpaces(const Level& level, const FreeSpaceOptions& options) {
  FreeSpaceRooms rooms;
  Grid grid = drawWalls(level, options);
  rooms.cell = grid.cell;
  if (grid.width == 0) return rooms;
  const int regions = labelRegions(grid);
  std::vector<RegionExtent> extents(std::size_t(regions) + 1);
  for (int j = 0; j < grid.height; ++j) {
    for (int i = 0; i < grid.width; ++i) {
      const int label = grid.region[std::size_t(grid.index(i, j))];
      if (label <= 0) continue;
      RegionExtent& e = extents[std::size_t(label)];
      ++e.cells;
      e.i0 = std::min(e.i0, i), e.j0 = std::min(e.j0, j);
      e.i1 = std::max(e.i1, i), e.j1 = std::max(e.j1, j);
    }
  }
  for (int label = 1; label <= regions; ++label) {
    const RegionExtent& extent = extents[std::size_t(label)];
    if (double(extent.cells) * grid.cell * grid.cell < options.min_area) {
      ++rooms.pockets;
      continue;
    }
    Polygon2 outer;
    for (const auto& loop : boundaryLoops(grid, label, extent)) {
      Polygon2 corners = cornersInMetres(grid, loop);
      if (corners.size() >= 3 && signedArea(corners) > signedArea(outer))
        outer = std::move(corners);
    }
    if (outer.size() < 3) continue;
    rooms.outlines.push_back(straightened(outer, grid.cell));
  }
  return rooms;
}

}  // namespace isg::bim
