#include "raster/raster_walls.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <unordered_map>

#include "raster/raster_skeleton.hpp"

namespace isg::raster {
namespace {

using Vec2 = Eigen::Vector2d;

constexpr double kPi = 3.14159265358979323846;

Vec2 perpendicular(const Vec2& d) { return Vec2(-d.y(), d.x()); }

// The image in pixel units, y up: pixel (column c, row r) covers [c, c + 1] × [H − r − 1, H − r].
struct PixelGrid {
  const OccupancyImage& image;
  bool occupied(const Vec2& p) const {
    if (!(p.x() >= 0.0) || !(p.y() >= 0.0)) return false;
    const int c = int(p.x()), up = int(p.y());
    if (c >= image.width || up >= image.height) return false;
    return image.pixels[std::size_t(image.height - 1 - up) * image.width + c] ==
           PixelClass::kOccupied;
  }
  Vec2 centre(std::size_t index) const {
    const int c = int(index % image.width), r = int(index / image.width);
    return Vec2(c + 0.5, image.height - r - 0.5);
  }
};

// A straight run of wall being fitted, in pixel units.
struct Piece {
  Vec2 point, direction;      // a point of the axis and its unit direction
  double lo = 0.0, hi = 0.0;  // the axis's extent: point + s · direction, s in [lo, hi]
  double thickness = 0.0;
  int node_lo = -1, node_hi = -1;  // the skeleton node each end meets (−1: a free end)
  bool alive = true;
  bool measured = false;  // its thickness measured across it (a stub inside a junction is not)
  int region = 0;
  Vec2 at(double s) const { return point + s * direction; }
  Vec2 normal() const { return perpendicular(direction); }
  double along(const Vec2& p) const { return (p - point).dot(direction); }
  double across(const Vec2& p) const { return (p - point).dot(normal()); }
};

// Total least squares line through points.
bool fitLine(const std::vector<Vec2>& points, Vec2& point, Vec2& direction) {
  if (points.size() < 2) return false;
  Vec2 mean = Vec2::Zero();
  for (const auto& p : points) mean += p;
  mean /= double(points.size());
  double sxx = 0, sxy = 0, syy = 0;
  for (const auto& p : points) {
    const Vec2 d = p - mean;
    sxx += d.x() * d.x(), sxy += d.x() * d.y(), syy += d.y() * d.y();
  }
  const double angle = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  point = mean;
  direction = Vec2(std::cos(angle), std::sin(angle));
  return sxx + syy > 0.0;
}

// The occupied run across the axis at p: how far it reaches to either side along n, to the edge
// between the last occupied sample and the first free one (quarter-pixel steps).
bool runAcross(const PixelGrid& grid, const Vec2& p, const Vec2& n, double max_half, double* minus,
               double* plus) {
  constexpr double kStep = 0.25;
  if (!grid.occupied(p)) return false;
  double b = 0.0;
  while (b < max_half && grid.occupied(p + (b + kStep) * n)) b += kStep;
  double a = 0.0;
  while (a < max_half && grid.occupied(p - (a + kStep) * n)) a += kStep;
  if (a >= max_half || b >= max_half) return false;
  *plus = b + 0.5 * kStep;
  *minus = a + 0.5 * kStep;
  return true;
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + values.size() / 2;
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// The axis moved to the middle of the occupied runs across it, sampled along [lo, hi], and the
// thickness their median width. Samples whose width is far from the median (where another wall
// meets this one, a door's jamb) are left out.
bool refineAcross(const PixelGrid& grid, double max_half, Piece& piece) {
  for (int iteration = 0; iteration < 3; ++iteration) {
    const double length = piece.hi - piece.lo;
    const int samples = std::clamp(int(length), 3, 1500);
    std::vector<double> s, middle, width;
    const Vec2 n = piece.normal();
    for (int k = 0; k < samples; ++k) {
      const double at = piece.lo + (k + 0.5) * length / samples;
      double minus = 0, plus = 0;
      if (!runAcross(grid, piece.at(at), n, max_half, &minus, &plus)) continue;
      s.push_back(at);
      middle.push_back(0.5 * (plus - minus));
      width.push_back(plus + minus);
    }
    if (width.size() < 3) return iteration > 0;
    const double typical = median(width);
    const double tolerance = std::max(1.5, 0.15 * typical);
    double sw = 0, ss = 0, sm = 0, sss = 0, ssm = 0;
    std::vector<double> kept;
    for (std::size_t k = 0; k < width.size(); ++k) {
      if (std::abs(width[k] - typical) > tolerance) continue;
      sw += 1, ss += s[k], sm += middle[k], sss += s[k] * s[k], ssm += s[k] * middle[k];
      kept.push_back(width[k]);
    }
    if (kept.size() < 3) return iteration > 0;
    const double determinant = sw * sss - ss * ss;
    double alpha = sm / sw, beta = 0.0;
    if (determinant > 1e-9 * sw * sss && length > 4.0) {
      beta = (sw * ssm - ss * sm) / determinant;
      alpha = (sm - beta * ss) / sw;
    }
    piece.thickness = median(kept);
    if (std::abs(beta) > 0.2 || std::abs(alpha) > piece.thickness + 2.0) return true;
    piece.point += alpha * n;
    piece.direction = (piece.direction + beta * n).normalized();
    if (std::abs(alpha) < 0.01 && std::abs(beta) < 1e-5) break;
  }
  return true;
}

// Douglas–Peucker: the indices of the chain's vertices kept within `tolerance` of it.
std::vector<int> simplify(const std::vector<Vec2>& chain, double tolerance) {
  std::vector<char> keep(chain.size(), 0);
  keep.front() = keep.back() = 1;
  std::vector<std::pair<int, int>> stack{{0, int(chain.size()) - 1}};
  while (!stack.empty()) {
    const auto [a, b] = stack.back();
    stack.pop_back();
    if (b - a < 2) continue;
    const Vec2 d = chain[b] - chain[a];
    const double length = d.norm();
    double worst = -1.0;
    int at = -1;
    for (int k = a + 1; k < b; ++k) {
      const Vec2 e = chain[k] - chain[a];
      const double distance =
          length > 1e-9 ? std::abs(d.x() * e.y() - d.y() * e.x()) / length : e.norm();
      if (distance > worst) worst = distance, at = k;
    }
    if (worst > tolerance) {
      keep[at] = 1;
      stack.push_back({a, at});
      stack.push_back({at, b});
    }
  }
  std::vector<int> out;
  for (int k = 0; k < int(chain.size()); ++k) {
    if (keep[k]) out.push_back(k);
  }
  return out;
}

// Where the lines of two pieces cross, as s along `a`; false when they are too parallel.
bool crossing(const Piece& a, const Piece& b, double min_sine, double* s) {
  const double sine = a.direction.x() * b.direction.y() - a.direction.y() * b.direction.x();
  if (std::abs(sine) < min_sine) return false;
  const Vec2 d = b.point - a.point;
  *s = (d.x() * b.direction.y() - d.y() * b.direction.x()) / sine;
  return true;
}

// Moves a free end to the region's edge along the axis.
double edgeAlongAxis(const PixelGrid& grid, const Piece& piece, double s, double sign,
                     double reach) {
  constexpr double kStep = 0.25;
  double t = 0.0;
  while (t < reach && grid.occupied(piece.at(s + sign * (t + kStep)))) t += kStep;
  return s + sign * (t + 0.5 * kStep);
}

bool insideFootprint(const Piece& wall, const Vec2& p, double margin) {
  const double along = wall.along(p);
  return std::abs(wall.across(p)) <= 0.5 * wall.thickness + margin &&
         along >= wall.lo - 0.5 * wall.thickness - margin &&
         along <= wall.hi + 0.5 * wall.thickness + margin;
}

// A place in the image's metres as the plan's coordinates, for a message.
std::string where(const Vec2& p_metres, const RasterWallOptions& options) {
  const Vec2 p = options.origin + Eigen::Rotation2Dd(options.yaw) * p_metres;
  char text[64];
  std::snprintf(text, sizeof text, "(%.2f, %.2f)", p.x(), p.y());
  return text;
}

struct Region {
  std::vector<std::uint32_t> pixels;
  int min_c, max_c, min_r, max_r;
  int image_width;
};

// Regions of occupied pixels, 8-connected, in scan order of their first pixel.
std::vector<Region> occupiedRegions(const OccupancyImage& image) {
  std::vector<Region> regions;
  std::vector<std::uint8_t> seen(image.pixels.size(), 0);
  std::vector<std::uint32_t> stack;
  const int w = image.width, h = image.height;
  for (std::size_t start = 0; start < image.pixels.size(); ++start) {
    if (seen[start] || image.pixels[start] != PixelClass::kOccupied) continue;
    Region region{{}, w, -1, h, -1, w};
    seen[start] = 1;
    stack.assign(1, std::uint32_t(start));
    while (!stack.empty()) {
      const std::uint32_t index = stack.back();
      stack.pop_back();
      region.pixels.push_back(index);
      const int c = int(index % w), r = int(index / w);
      region.min_c = std::min(region.min_c, c), region.max_c = std::max(region.max_c, c);
      region.min_r = std::min(region.min_r, r), region.max_r = std::max(region.max_r, r);
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          const int nc = c + dc, nr = r + dr;
          if (nc < 0 || nr < 0 || nc >= w || nr >= h) continue;
          const std::size_t next = std::size_t(nr) * w + nc;
          if (seen[next] || image.pixels[next] != PixelClass::kOccupied) continue;
          seen[next] = 1;
          stack.push_back(std::uint32_t(next));
        }
      }
    }
    std::sort(region.pixels.begin(), region.pixels.end());
    regions.push_back(std::move(region));
  }
  return regions;
}

// The region's pixels and every pixel it encloses (its holes), counted in its box.
std::size_t withHolesFilled(const Region& region) {
  const int w = region.max_c - region.min_c + 3, h = region.max_r - region.min_r + 3;
  const int image_width = region.image_width;
  std::vector<std::uint8_t> cells(std::size_t(w) * h, 0);  // 1: the region's, 2: outside it
  for (auto index : region.pixels) {
    const int c = int(index % image_width) - region.min_c + 1;
    const int row = int(index / image_width) - region.min_r + 1;
    cells[std::size_t(row) * w + c] = 1;
  }
  std::vector<int> stack{0};
  cells[0] = 2;
  std::size_t outside = 0;
  while (!stack.empty()) {
    const int i = stack.back();
    stack.pop_back();
    ++outside;
    const int c = i % w, row = i / w;
    const int next[4] = {c > 0 ? i - 1 : -1, c + 1 < w ? i + 1 : -1, row > 0 ? i - w : -1,
                         row + 1 < h ? i + w : -1};
    for (int j : next) {
      if (j >= 0 && cells[j] == 0) cells[j] = 2, stack.push_back(j);
    }
  }
  return std::size_t(w) * h - outside;
}

// The region's principal axes: its pixels' mean, the long axis, and the extents along both.
struct Box {
  Vec2 centre, axis;
  double length = 0, width = 0;
};

// The box of the region's pixels with its long side along `axis`.
Box boxAlong(const PixelGrid& grid, const Region& region, const Vec2& mean, Vec2 axis) {
  Vec2 across = perpendicular(axis);
  double lo1 = 1e300, hi1 = -1e300, lo2 = 1e300, hi2 = -1e300;
  for (auto index : region.pixels) {
    const Vec2 d = grid.centre(index) - mean;
    lo1 = std::min(lo1, d.dot(axis)), hi1 = std::max(hi1, d.dot(axis));
    lo2 = std::min(lo2, d.dot(across)), hi2 = std::max(hi2, d.dot(across));
  }
  // A pixel's own extent along a direction at angle θ to the grid is |cos θ| + |sin θ|.
  const double pixel = std::abs(axis.x()) + std::abs(axis.y());
  Box box;
  box.centre = mean + 0.5 * (lo1 + hi1) * axis + 0.5 * (lo2 + hi2) * across;
  box.length = hi1 - lo1 + pixel;
  box.width = hi2 - lo2 + pixel;
  box.axis = axis;
  if (box.width > box.length) {
    std::swap(box.width, box.length);
    box.axis = across;
  }
  return box;
}

// The region's box: along its principal axis, or — for a region small enough to be a column,
// whose principal axes say nothing when it is square — the smallest over every whole degree.
Box orientedBox(const PixelGrid& grid, const Region& region, double search_below) {
  Vec2 mean = Vec2::Zero();
  for (auto index : region.pixels) mean += grid.centre(index);
  mean /= double(region.pixels.size());
  double sxx = 0, sxy = 0, syy = 0;
  for (auto index : region.pixels) {
    const Vec2 d = grid.centre(index) - mean;
    sxx += d.x() * d.x(), sxy += d.x() * d.y(), syy += d.y() * d.y();
  }
  const double angle = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  Box best = boxAlong(grid, region, mean, Vec2(std::cos(angle), std::sin(angle)));
  if (best.length > search_below) return best;
  for (int degree = 0; degree < 90; ++degree) {
    const double a = degree * kPi / 180.0;
    const Box box = boxAlong(grid, region, mean, Vec2(std::cos(a), std::sin(a)));
    if (box.length * box.width < best.length * best.width) best = box;
  }
  return best;
}

// The trace's state from step to step: the pieces of wall found so far (in pixel units), the
// skeleton nodes their ends meet, and what is written out.
struct Trace {
  const OccupancyImage& image;
  const RasterWallOptions& options;
  double r;  // metres a pixel
  PixelGrid grid;
  std::vector<Piece> pieces;
  int next_node = 0;
  std::vector<std::pair<int, std::size_t>> region_pieces;  // (region, first piece)
  RasterWalls out;
  Vec2 metres(const Vec2& p) const { return p * r; }
};

// Regions: a speck, a column or a symbol is settled at once (true); a region of walls is not.
bool settledAsSpeckColumnOrSymbol(Trace& trace, const Region& region) {
  const RasterWallOptions& options = trace.options;
  const double r = trace.r;
  const double area = double(region.pixels.size()) * r * r;
  if (area < options.min_region_area) {
    ++trace.out.specks;
    return true;
  }
  const Box box = orientedBox(trace.grid, region, 1.5 * options.max_column_size / r);
  // A pillar in a map made by a LiDAR is its outline around an inside never seen: what the
  // region encloses counts as its own when it is judged a column.
  const double fill =
      double(box.length * r <= 1.5 * options.max_column_size ? withHolesFilled(region)
                                                             : region.pixels.size()) /
      (box.length * box.width);
  const double aspect = box.length / std::max(box.width, 1.0);
  if (box.length * r <= options.max_column_size && aspect <= options.max_column_aspect &&
      fill >= options.min_column_fill) {
    RasterWall column;
    const bool round = fill < 0.88 && aspect < 1.15;
    const double side = round ? 0.5 * (box.length + box.width) : box.length;
    column.kind = round ? RasterWall::Kind::kRoundColumn : RasterWall::Kind::kColumn;
    column.start = trace.metres(box.centre - 0.5 * side * box.axis);
    column.end = trace.metres(box.centre + 0.5 * side * box.axis);
    column.thickness = (round ? side : box.width) * r;
    trace.out.walls.push_back(column);
    return true;
  }
  if (box.length * r <= options.max_symbol_size) {
    ++trace.out.symbols;
    trace.out.left_out.push_back("a mark of " + std::to_string(region.pixels.size()) +
                                 " pixels at " + where(trace.metres(box.centre), options) +
                                 " is neither a wall nor a column (text, a symbol?): left out");
    return true;
  }
  return false;
}

// Skeleton → pieces: the region thinned to its skeleton, each branch cut into straight runs,
// each run's line and thickness measured across it.
void addPiecesOfRegion(Trace& trace, const Region& region, int g) {
  const double max_half = 1.0 / trace.r;  // walls up to 2 m thick are measured across
  const Skeleton skeleton = thinRegion(trace.image, region.pixels, region.min_c, region.max_c,
                                       region.min_r, region.max_r);
  const double tolerance = std::max(1.5, 0.1 * 2.0 * skeleton.iterations);
  const int junction_base = trace.next_node;
  trace.next_node += skeleton.junctions;
  const auto node = [junction_base](int junction) {
    return junction >= 0 ? junction_base + junction : -1;
  };
  trace.region_pieces.push_back({g, trace.pieces.size()});
  for (const SkeletonChain& chain : skeleton.chains) {
    if (chain.pixels.size() < 2) continue;
    std::vector<Vec2> points;
    points.reserve(chain.pixels.size());
    for (auto index : chain.pixels) points.push_back(trace.grid.centre(index));
    const std::vector<int> vertices = simplify(points, tolerance);
    int previous_node = node(chain.node_front);
    for (std::size_t v = 0; v + 1 < vertices.size(); ++v) {
      const int a = vertices[v], b = vertices[v + 1];
      const bool last = v + 2 == vertices.size();
      const int end_node = last ? node(chain.node_back) : trace.next_node++;
      // The run's line from its middle part: a junction bends the skeleton near its ends.
      const int trim = std::min((b - a) / 4, int(skeleton.iterations));
      std::vector<Vec2> run(points.begin() + a + trim, points.begin() + b + 1 - trim);
      Piece piece;
      piece.region = g;
      if (!fitLine(run, piece.point, piece.direction)) {
        piece.point = points[a];
        piece.direction = (points[b] - points[a]).normalized();
      }
      if ((points[b] - points[a]).dot(piece.direction) < 0) piece.direction = -piece.direction;
      piece.lo = piece.along(points[a]);
      piece.hi = piece.along(points[b]);
      piece.node_lo = previous_node;
      piece.node_hi = end_node;
      if (!(piece.hi - piece.lo > 0.5)) {
        previous_node = end_node;
        continue;
      }
      // Until measured: the region's thickest wall, as thinning took it.
      piece.thickness = 2.0 * skeleton.iterations;
      piece.measured = refineAcross(trace.grid, max_half, piece);
      piece.lo = piece.along(points[a]);
      piece.hi = piece.along(points[b]);
      trace.pieces.push_back(piece);
      previous_node = end_node;
    }
  }
}

// A junction of walls joins a handful of runs; a node of hundreds is a tangle (noise, hatching)
// where comparing every run there with every other would cost their square (a 9 Mpx noise image:
// minutes). At a node of more runs than this, each run is compared with the longest this many
// only: exact wherever walls meet, bounded where they do not.
constexpr std::size_t kMaxRunsAtJunction = 64;

// The pieces as a graph of skeleton nodes: which pieces meet at each node, and nodes merged into
// one where a run between them goes.
class PieceGraph {
 public:
  PieceGraph(std::vector<Piece>& pieces, int nodes)
      : pieces_(pieces),
        nodes_(nodes),
        node_parent_(nodes),
        thickest_(nodes, 0.0),
        pieces_at_(nodes) {
    std::iota(node_parent_.begin(), node_parent_.end(), 0);
    for (const auto& piece : pieces_) {
      if (!piece.measured) continue;
      for (int node : {piece.node_lo, piece.node_hi}) {
        if (node >= 0) thickest_[node] = std::max(thickest_[node], piece.thickness);
      }
    }
    for (int i = 0; i < int(pieces_.size()); ++i) {
      if (pieces_[i].node_lo >= 0) pieces_at_[pieces_[i].node_lo].push_back(i);
      if (pieces_[i].node_hi >= 0) pieces_at_[pieces_[i].node_hi].push_back(i);
    }
    // Only the longest kMaxRunsAtJunction runs of a tangle are neighbours (see there).
    for (auto& at : pieces_at_) {
      if (at.size() <= kMaxRunsAtJunction) continue;
      std::stable_sort(at.begin(), at.end(), [&](int a, int b) {
        return pieces_[a].hi - pieces_[a].lo > pieces_[b].hi - pieces_[b].lo;
      });
      at.resize(kMaxRunsAtJunction);
    }
  }

  int root(int i) {
    while (node_parent_[i] != i) i = node_parent_[i] = node_parent_[node_parent_[i]];
    return i;
  }
  void merge(int a, int b) { node_parent_[root(a)] = root(b); }
  double thickest(int node) const { return thickest_[node]; }

  // An end that meets no other live run at its node is free.
  void freeLonelyEnds() {
    std::vector<int> ends_at(nodes_, 0);
    for (auto& piece : pieces_) {
      if (piece.node_lo >= 0) piece.node_lo = root(piece.node_lo);
      if (piece.node_hi >= 0) piece.node_hi = root(piece.node_hi);
      if (!piece.alive) continue;
      if (piece.node_lo >= 0) ++ends_at[piece.node_lo];
      if (piece.node_hi >= 0) ++ends_at[piece.node_hi];
    }
    for (auto& piece : pieces_) {
      if (piece.node_lo >= 0 && ends_at[piece.node_lo] < 2) piece.node_lo = -1;
      if (piece.node_hi >= 0 && ends_at[piece.node_hi] < 2) piece.node_hi = -1;
    }
  }

  // A run inside the solid of a longer run it meets is no wall: the skeleton's spurs (thinning
  // leaves one at a convex corner, a fork at a wall's square end) and its bends where walls meet.
  bool insideANeighbour(int i) const {
    const Piece& piece = pieces_[i];
    for (int node : {piece.node_lo, piece.node_hi}) {
      if (node < 0) continue;
      for (int j : pieces_at_[node]) {
        const Piece& other = pieces_[j];
        if (j == i || !other.alive || other.hi - other.lo < piece.hi - piece.lo) continue;
        const double margin = std::max(2.0, 0.1 * other.thickness);
        if (insideFootprint(other, piece.at(piece.lo), margin) &&
            insideFootprint(other, piece.at(piece.hi), margin))
          return true;
      }
    }
    return false;
  }

  // Whether a run leaves its node in some other run's direction (a stub of wall runs on from a
  // wall it continues; thinning's spurs run diagonally into a corner).
  bool alignedWithANeighbour(int i, int node) const {
    const double cos_aligned = std::cos(15.0 * kPi / 180.0);
    for (int j : pieces_at_[node]) {
      if (j != i && std::abs(pieces_[i].direction.dot(pieces_[j].direction)) >= cos_aligned)
        return true;
    }
    return false;
  }

 private:
  std::vector<Piece>& pieces_;
  int nodes_;
  std::vector<int> node_parent_;
  std::vector<double> thickest_;
  std::vector<std::vector<int>> pieces_at_;
};

// Joints: runs shorter than the walls they join at both ends are the skeleton's bends where walls
// meet (thinning rounds a corner over about half a wall's thickness): they go, and the nodes at
// their two ends become one, so that the walls on either side meet there.
void dropSpursAndBends(std::vector<Piece>& pieces, int nodes) {
  PieceGraph graph(pieces, nodes);
  // A short branch with a free end that leaves its node in no wall's direction.
  for (int i = 0; i < int(pieces.size()); ++i) {
    Piece& piece = pieces[i];
    if ((piece.node_lo >= 0) == (piece.node_hi >= 0)) continue;
    const int node = std::max(piece.node_lo, piece.node_hi);
    if (graph.insideANeighbour(i) ||
        (piece.hi - piece.lo < graph.thickest(node) && !graph.alignedWithANeighbour(i, node)))
      piece.alive = false;
  }
  graph.freeLonelyEnds();
  // Then runs between two nodes inside a neighbour or shorter than the walls they join (a
  // wall's bend round a corner): they go, and their two nodes become one.
  for (int i = 0; i < int(pieces.size()); ++i) {
    Piece& piece = pieces[i];
    if (!piece.alive || piece.node_lo < 0 || piece.node_hi < 0) continue;
    const double join = std::max(graph.thickest(piece.node_lo), graph.thickest(piece.node_hi));
    if (piece.hi - piece.lo >= 0.75 * join && !graph.insideANeighbour(i)) continue;
    piece.alive = false;
    graph.merge(piece.node_lo, piece.node_hi);
  }
  graph.freeLonelyEnds();
}

// The live pieces' ends grouped by the node they meet: node → (piece, end 0 low / 1 high).
std::vector<std::vector<std::pair<int, int>>> endsByNode(const std::vector<Piece>& pieces) {
  std::vector<std::vector<std::pair<int, int>>> at_node;
  std::vector<std::pair<int, std::pair<int, int>>> ends;
  for (int i = 0; i < int(pieces.size()); ++i) {
    if (!pieces[i].alive) continue;
    if (pieces[i].node_lo != -1) ends.push_back({pieces[i].node_lo, {i, 0}});
    if (pieces[i].node_hi != -1) ends.push_back({pieces[i].node_hi, {i, 1}});
  }
  std::sort(ends.begin(), ends.end());
  for (std::size_t k = 0; k < ends.size();) {
    std::size_t e = k;
    std::vector<std::pair<int, int>> group;
    while (e < ends.size() && ends[e].first == ends[k].first) group.push_back(ends[e++].second);
    at_node.push_back(std::move(group));
    k = e;
  }
  return at_node;
}

// Bends: two runs meeting at a node turned by a few degrees to a few tens, as a curved wall's
// straight pieces do. Each region with such a chain says so.
void reportBends(Trace& trace, const std::vector<std::vector<std::pair<int, int>>>& at_node) {
  const double slight = 3.0 * kPi / 180.0, sharp = 30.0 * kPi / 180.0;
  std::vector<std::pair<int, Vec2>> bends;  // (region, where)
  for (const auto& group : at_node) {
    if (group.size() != 2) continue;
    const Piece& a = trace.pieces[group[0].first];
    const Piece& b = trace.pieces[group[1].first];
    const double turn = std::acos(std::min(1.0, std::abs(a.direction.dot(b.direction))));
    if (turn > slight && turn < sharp) {
      bends.push_back({a.region, a.at(group[0].second == 0 ? a.lo : a.hi)});
    }
  }
  std::sort(bends.begin(), bends.end(),
            [](const auto& x, const auto& y) { return x.first < y.first; });
  for (std::size_t k = 0; k < bends.size();) {
    std::size_t e = k;
    Vec2 sum = Vec2::Zero();
    while (e < bends.size() && bends[e].first == bends[k].first) sum += bends[e++].second;
    if (e - k >= 2) {
      trace.out.left_out.push_back(
          "a curved wall around " + where(trace.metres(sum / double(e - k)), trace.options) +
          ": simplified to straight walls (" + std::to_string(e - k) + " bends of 3–30°)");
    }
    k = e;
  }
}

// Ends: against the runs they meet at a node (where their fitted lines cross, the most crossing
// one), or out to the region's edge when free.
void closeEnds(std::vector<Piece>& pieces,
               const std::vector<std::vector<std::pair<int, int>>>& at_node,
               const PixelGrid& grid) {
  const double min_sine = std::sin(20.0 * kPi / 180.0);
  std::vector<Piece> before = pieces;  // ends set from the fitted lines, not from moved ends
  std::vector<std::pair<int, int>> longest;
  for (const auto& group : at_node) {
    const std::vector<std::pair<int, int>>* others = &group;
    if (group.size() > kMaxRunsAtJunction) {  // a tangle: its longest runs only
      longest = group;
      std::stable_sort(longest.begin(), longest.end(), [&](const auto& a, const auto& b) {
        return before[a.first].hi - before[a.first].lo > before[b.first].hi - before[b.first].lo;
      });
      longest.resize(kMaxRunsAtJunction);
      others = &longest;
    }
    for (const auto& [i, end] : group) {
      const Piece& mine = before[i];
      const double s_end = end == 0 ? mine.lo : mine.hi;
      double best_sine = 0.0, best_s = s_end;
      for (const auto& [j, other_end] : *others) {
        if (j == i) continue;
        double s = 0.0;
        if (!crossing(mine, before[j], min_sine, &s)) continue;
        const double reach = 3.0 * std::max(mine.thickness, before[j].thickness) + 3.0;
        if (std::abs(s - s_end) > reach) continue;
        const double sine = std::abs(mine.direction.x() * before[j].direction.y() -
                                     mine.direction.y() * before[j].direction.x());
        if (sine > best_sine) best_sine = sine, best_s = s;
      }
      (end == 0 ? pieces[i].lo : pieces[i].hi) = best_s;
    }
  }
  for (auto& piece : pieces) {
    if (!piece.alive) continue;
    const double reach = 2.0 * piece.thickness + 3.0;
    if (piece.node_lo == -1) piece.lo = edgeAlongAxis(grid, piece, piece.lo, -1.0, reach);
    if (piece.node_hi == -1) piece.hi = edgeAlongAxis(grid, piece, piece.hi, +1.0, reach);
  }
}

// The cells of a square grid each run's footprint (insideFootprint with `margin`) touches: the
// footprint is an oriented rectangle, and each row of cells gets the span of columns the rectangle
// crosses in that row, so a long diagonal run costs its cells, not its bounding box.
class FootprintGrid {
 public:
  static constexpr double kCell = 16.0;  // pixels

  // Each live run's footprint grown by margin(run) pixels.
  template <typename Margin>
  FootprintGrid(const std::vector<Piece>& pieces, const Margin& margin) {
    for (int i = 0; i < int(pieces.size()); ++i) {
      if (!pieces[i].alive) continue;
      forEachCell(pieces[i], 0.5 * pieces[i].thickness + margin(pieces[i]),
                  [&](std::int64_t cell) { cells_[cell].push_back(i); });
    }
  }

  // The runs whose grown footprint may hold `p`.
  const std::vector<int>& piecesNear(const Vec2& p) const {
    const auto found = cells_.find(key(cellOf(p.x()), cellOf(p.y())));
    return found == cells_.end() ? none_ : found->second;
  }

  // Every run whose grown footprint may meet `piece`'s axis (a run may come more than once).
  template <typename Visit>
  void forEachNearSegment(const Piece& piece, const Visit& visit) const {
    forEachCell(piece, 0.5, [&](std::int64_t cell) {
      const auto found = cells_.find(cell);
      if (found == cells_.end()) return;
      for (const int j : found->second) visit(j);
    });
  }

 private:
  // The cells an oriented rectangle meets: the axis from lo − half to hi + half, `half` either
  // side; each row of cells gets the span of columns the rectangle's edges cross in that row.
  template <typename Visit>
  static void forEachCell(const Piece& piece, double half, const Visit& visit) {
    const Vec2 a = piece.at(piece.lo - half), b = piece.at(piece.hi + half);
    const Vec2 side = half * piece.normal();
    const std::array<Vec2, 4> corner = {a - side, b - side, b + side, a + side};
    double y_min = corner[0].y(), y_max = y_min;
    for (const Vec2& c : corner) y_min = std::min(y_min, c.y()), y_max = std::max(y_max, c.y());
    for (long row = cellOf(y_min); row <= cellOf(y_max); ++row) {
      const double lo = std::max(y_min, double(row) * kCell);
      const double hi = std::min(y_max, double(row + 1) * kCell);
      double x_min = 1e300, x_max = -1e300;
      for (int k = 0; k < 4; ++k) {  // the rectangle's edges clipped to the row's band
        const Vec2& p = corner[k];
        const Vec2& q = corner[(k + 1) % 4];
        const double y0 = std::max(lo, std::min(p.y(), q.y()));
        const double y1 = std::min(hi, std::max(p.y(), q.y()));
        if (y0 > y1) continue;
        if (q.y() == p.y()) {
          x_min = std::min({x_min, p.x(), q.x()}), x_max = std::max({x_max, p.x(), q.x()});
          continue;
        }
        for (const double y : {y0, y1}) {
          const double x = p.x() + (q.x() - p.x()) * (y - p.y()) / (q.y() - p.y());
          x_min = std::min(x_min, x), x_max = std::max(x_max, x);
        }
      }
      for (long column = cellOf(x_min); column <= cellOf(x_max); ++column) {
        visit(key(column, row));
      }
    }
  }
  static long cellOf(double v) { return long(std::floor(v / kCell)); }
  static std::int64_t key(long column, long row) {
    return (std::int64_t(row) << 32) ^ std::int64_t(std::uint32_t(column));
  }
  std::unordered_map<std::int64_t, std::vector<int>> cells_;
  std::vector<int> none_;
};

// The runs that are walls: not inside another wall's solid (the skeleton's spurs at corners, its
// bends at junctions), long enough, and not thicker than twice their length (thinning's tangle
// where short walls and openings meet; what it leaves uncovered is said later).
std::vector<Piece> wallRuns(std::vector<Piece>& pieces, const RasterWallOptions& options,
                            double r) {
  // Which runs could hold a point: each run's footprint (margin included) in the cells of a
  // grid it covers, so that a run is compared with the runs around its end, not with every run.
  const FootprintGrid grid(pieces, [](const Piece&) { return 2.0; });
  for (int i = 0; i < int(pieces.size()); ++i) {
    if (!pieces[i].alive) continue;
    for (const int j : grid.piecesNear(pieces[i].at(pieces[i].lo))) {
      if (i == j || !pieces[j].alive || pieces[j].region != pieces[i].region) continue;
      if (pieces[j].hi - pieces[j].lo < pieces[i].hi - pieces[i].lo) continue;
      if (insideFootprint(pieces[j], pieces[i].at(pieces[i].lo), 2.0) &&
          insideFootprint(pieces[j], pieces[i].at(pieces[i].hi), 2.0)) {
        pieces[i].alive = false;
        break;
      }
    }
  }
  std::vector<Piece> kept;
  for (const auto& piece : pieces) {
    const double length = piece.hi - piece.lo;
    if (piece.alive && length * r >= options.min_wall_length && piece.thickness <= 2.0 * length)
      kept.push_back(piece);
  }
  return kept;
}

// Whether the line is free of occupied pixels between `from` and `to` (a doorway).
bool gapIsOpen(const PixelGrid& grid, const Piece& line, double from, double to) {
  for (double s = from + 0.5; s < to - 0.5; s += 0.5) {
    if (grid.occupied(line.at(s))) return false;
  }
  return true;
}

// Whether two runs of about one direction are one wall: in line across, of about one thickness,
// touching or with a doorway between them.
bool oneWall(const PixelGrid& grid, const Piece& p, Piece q, double door_min, double door_max) {
  if (p.direction.dot(q.direction) < 0) {
    q.direction = -q.direction;
    std::swap(q.lo, q.hi);
    q.lo = -q.lo, q.hi = -q.hi;
  }
  // Across: the facing ends against each other's line (a short run's small turn must not count
  // over a long one's length).
  const double lateral_limit = std::max(2.0, 0.2 * std::min(p.thickness, q.thickness));
  const bool q_after = p.along(q.at(0.5 * (q.lo + q.hi))) > 0.5 * (p.lo + p.hi);
  const Vec2 p_near = p.at(q_after ? p.hi : p.lo), q_near = q.at(q_after ? q.lo : q.hi);
  if (std::abs(p.across(q_near)) > lateral_limit || std::abs(q.across(p_near)) > lateral_limit)
    return false;
  if (p.measured && q.measured &&
      std::max(p.thickness, q.thickness) > 1.35 * std::min(p.thickness, q.thickness) + 2.0)
    return false;
  const double q0 = p.along(q.at(q.lo)), q1 = p.along(q.at(q.hi));
  const double gap = std::max(q0 - p.hi, p.lo - q1);
  bool join = gap <= 2.0;
  if (!join && gap >= door_min && gap <= door_max) {
    join = q0 > p.hi ? gapIsOpen(grid, p, p.hi, q0) : gapIsOpen(grid, p, q1, p.lo);
  }
  return join;
}

// Collinear runs grouped into one wall each (indices into `kept`, groups by their root).
std::vector<std::vector<int>> collinearGroups(const std::vector<Piece>& kept, const PixelGrid& grid,
                                              const RasterWallOptions& options, double r) {
  std::vector<int> parent(kept.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  const double door_min = options.min_door_width / r, door_max = options.max_door_width / r;
  // Sorted by direction angle (mod π), pairs compared within the collinear tolerance.
  std::vector<std::pair<double, int>> by_angle;
  for (int i = 0; i < int(kept.size()); ++i) {
    double angle = std::atan2(kept[i].direction.y(), kept[i].direction.x());
    if (angle < 0) angle += kPi;
    if (angle >= kPi) angle -= kPi;
    by_angle.push_back({angle, i});
  }
  std::sort(by_angle.begin(), by_angle.end());
  // A short run's direction is known only to about two pixels over its length: two runs are
  // collinear within collinear_angle, or within that uncertainty of the shorter one (at most 8°).
  const double base_angle = options.collinear_angle * kPi / 180.0, max_angle = 8.0 * kPi / 180.0;
  const auto allowedTurn = [&](const Piece& p, const Piece& q) {
    const double shorter = std::min(p.hi - p.lo, q.hi - q.lo);
    return std::clamp(std::atan2(2.0, shorter), base_angle, max_angle);
  };
  const double window = max_angle;
  const std::size_t n_angle = by_angle.size();
  // Each run is compared with the runs after it in angle order, up to the first beyond the
  // window (cyclically: past π the angles start again). Comparing every such pair costs the
  // square of the runs on a noisy image; only runs near each other can be one wall (their gap at
  // most a door, their offset a few pixels), so the pairs are taken from a grid of the runs'
  // footprints grown by that reach, and each is kept when the angle order would have reached it.
  std::vector<std::size_t> position(n_angle);
  std::vector<double> angles(n_angle);
  for (std::size_t k = 0; k < n_angle; ++k) {
    position[by_angle[k].second] = k;
    angles[k] = by_angle[k].first;
  }
  // How many steps from position a the angle order goes before an angle beyond the window.
  const auto reach = [&](std::size_t a) -> std::size_t {
    const double angle = angles[a];
    const auto first_beyond = std::size_t(
        std::upper_bound(angles.begin() + a + 1, angles.end(), angle + window) - angles.begin());
    if (first_beyond < n_angle) return first_beyond - a - 1;
    // Past π: the angles below this one come round at angle + π, then those equal to it at 0.
    const auto first_equal =
        std::size_t(std::lower_bound(angles.begin(), angles.begin() + a, angle) - angles.begin());
    const auto wrapped_beyond = std::size_t(
        std::upper_bound(angles.begin(), angles.begin() + first_equal, angle + window - kPi) -
        angles.begin());
    if (wrapped_beyond < first_equal) return n_angle - 1 - a + wrapped_beyond;
    return n_angle - 1;
  };
  const FootprintGrid near(kept, [&](const Piece& piece) {
    return std::max(2.0, door_max) + std::max(2.0, 0.2 * piece.thickness) + 4.0;
  });
  std::vector<std::size_t> last_seen(kept.size(), kept.size());
  for (std::size_t i = 0; i < kept.size(); ++i) {
    const std::size_t a = position[i];
    const std::size_t a_reach = reach(a);
    const auto compare = [&](std::size_t from, std::size_t to) {  // positions, as the order goes
      double difference = angles[to] - angles[from];
      if (difference < 0) difference += kPi;
      const Piece& p = kept[by_angle[from].second];
      const Piece& q = kept[by_angle[to].second];
      if (difference > allowedTurn(p, q)) return;
      if (oneWall(grid, p, q, door_min, door_max))
        parent[root(by_angle[from].second)] = root(by_angle[to].second);
    };
    near.forEachNearSegment(kept[i], [&](int j) {
      if (std::size_t(j) == i || last_seen[j] == i) return;
      last_seen[j] = i;
      // Compared in each direction the angle order goes from one to the other.
      const std::size_t b = position[j];
      const std::size_t steps = (b + n_angle - a) % n_angle;
      if (steps <= a_reach) compare(a, b);
      const std::size_t back = (a + n_angle - b) % n_angle;
      if (back <= reach(b)) compare(b, a);  // a pair met twice is joined twice: no matter
    });
  }
  std::vector<std::vector<int>> groups(kept.size());
  for (int i = 0; i < int(kept.size()); ++i) groups[root(i)].push_back(i);
  return groups;
}

// One group's walls: its line (length-weighted direction and offset), the solid stretches along
// it, and consecutive stretches with a doorway between them as one wall with that door.
void addWallsOfGroup(Trace& trace, const std::vector<Piece>& kept, const std::vector<int>& group) {
  const double r = trace.r;
  const double door_min = trace.options.min_door_width / r,
               door_max = trace.options.max_door_width / r;
  Vec2 direction = Vec2::Zero(), point = Vec2::Zero();
  double total = 0.0, thickness = 0.0, measured = 0.0;
  const Vec2 reference = kept[group.front()].direction;
  for (int i : group) {
    const double length = kept[i].hi - kept[i].lo;
    const Vec2 d = kept[i].direction.dot(reference) < 0 ? -kept[i].direction : kept[i].direction;
    direction += length * d;
    point += length * kept[i].at(0.5 * (kept[i].lo + kept[i].hi));
    if (kept[i].measured) thickness += length * kept[i].thickness, measured += length;
    total += length;
  }
  Piece line;
  line.direction = direction.normalized();
  line.point = point / total;
  line.thickness = measured > 0.0 ? thickness / measured : kept[group.front()].thickness;
  std::vector<std::pair<double, double>> spans;
  for (int i : group) {
    double a = line.along(kept[i].at(kept[i].lo)), b = line.along(kept[i].at(kept[i].hi));
    if (a > b) std::swap(a, b);
    spans.push_back({a, b});
  }
  std::sort(spans.begin(), spans.end());
  // Solid stretches: spans that touch or overlap.
  std::vector<std::pair<double, double>> solid;
  for (const auto& span : spans) {
    if (!solid.empty() && span.first <= solid.back().second + 2.0) {
      solid.back().second = std::max(solid.back().second, span.second);
    } else {
      solid.push_back(span);
    }
  }
  std::size_t first = 0;
  for (std::size_t k = 0; k < solid.size(); ++k) {
    const bool last = k + 1 == solid.size();
    bool door_after = false;
    if (!last) {
      const double gap = solid[k + 1].first - solid[k].second;
      door_after = gap >= door_min && gap <= door_max &&
                   gapIsOpen(trace.grid, line, solid[k].second, solid[k + 1].first);
    }
    if (door_after) continue;
    RasterWall wall;
    wall.start = trace.metres(line.at(solid[first].first));
    wall.end = trace.metres(line.at(solid[k].second));
    wall.thickness = line.thickness * r;
    const int index = int(trace.out.walls.size());
    trace.out.walls.push_back(wall);
    for (std::size_t d = first; d < k; ++d) {
      RasterDoor door;
      door.wall = index;
      door.offset = (0.5 * (solid[d].second + solid[d + 1].first) - solid[first].first) * r;
      door.width = (solid[d + 1].first - solid[d].second) * r;
      trace.out.doors.push_back(door);
    }
    first = k + 1;
  }
}

// The pixels the walls found cover (1), with a pixel and a half to spare on each side.
std::vector<std::uint8_t> coveredByWalls(const Trace& trace) {
  const OccupancyImage& image = trace.image;
  const double r = trace.r;
  std::vector<std::uint8_t> covered(image.pixels.size(), 0);
  for (const auto& wall : trace.out.walls) {
    const Vec2 a = wall.start / r, b = wall.end / r;
    const double length = (b - a).norm();
    if (length <= 0.0) continue;
    const Vec2 d = (b - a) / length, n = perpendicular(d);
    const double half = 0.5 * wall.thickness / r + 1.5;
    for (double s = -half; s <= length + half; s += 0.5) {
      for (double o = -half; o <= half; o += 0.5) {
        const Vec2 p = a + s * d + o * n;
        if (p.x() < 0 || p.y() < 0 || p.x() >= image.width || p.y() >= image.height) continue;
        covered[std::size_t(image.height - 1 - int(p.y())) * image.width + int(p.x())] = 1;
      }
    }
  }
  return covered;
}

// The patch of uncovered dark pixels 8-connected to `start`, marked said (2): its size and the
// sum of its pixels' centres.
std::size_t floodUncovered(const Trace& trace, std::uint32_t start,
                           std::vector<std::uint8_t>& covered, Vec2& sum) {
  const OccupancyImage& image = trace.image;
  covered[start] = 2;
  std::vector<std::uint32_t> stack(1, start);
  std::size_t count = 0;
  while (!stack.empty()) {
    const std::uint32_t index = stack.back();
    stack.pop_back();
    ++count, sum += trace.grid.centre(index);
    const int c = int(index % image.width), row = int(index / image.width);
    for (int dr = -1; dr <= 1; ++dr) {
      for (int dc = -1; dc <= 1; ++dc) {
        const int nc = c + dc, nr = row + dr;
        if (nc < 0 || nr < 0 || nc >= image.width || nr >= image.height) continue;
        const std::size_t next = std::size_t(nr) * image.width + nc;
        if (covered[next] || image.pixels[next] != PixelClass::kOccupied) continue;
        covered[next] = 2;
        stack.push_back(std::uint32_t(next));
      }
    }
  }
  return count;
}

// What is left out: every patch of dark pixels the walls leave uncovered, of at least
// min_uncovered_area, within the regions that made walls, is said (the first 20 of them).
void reportUncovered(Trace& trace, const std::vector<Region>& regions) {
  const double r = trace.r;
  std::vector<std::uint8_t> covered = coveredByWalls(trace);
  int said = 0, unsaid = 0;
  for (const auto& [g, first_piece] : trace.region_pieces) {
    for (const auto start : regions[g].pixels) {
      if (covered[start]) continue;
      Vec2 sum = Vec2::Zero();
      const std::size_t count = floodUncovered(trace, start, covered, sum);
      if (double(count) * r * r < trace.options.min_uncovered_area) continue;
      if (said == 20) {
        ++unsaid;
        continue;
      }
      ++said;
      char text[200];
      std::snprintf(text, sizeof text,
                    "%.2f m² of dark pixels around %s are not straight walls (a curve, hatching, "
                    "text touching a wall, a tangle of short walls?): left out",
                    double(count) * r * r,
                    where(trace.metres(sum / double(count)), trace.options).c_str());
      trace.out.left_out.push_back(text);
    }
  }
  if (unsaid > 0) {
    trace.out.left_out.push_back("… and " + std::to_string(unsaid) +
                                 " more such patches (only the first 20 are listed)");
  }
}

}  // namespace

// Regions → skeleton → pieces → joints → walls along collinear runs → what is left out; columns
// and symbols are settled with their regions.
RasterWalls traceRasterWalls(const OccupancyImage& image, const RasterWallOptions& options) {
  const auto checkInterrupt = [&] {
    if (options.check_interrupt) options.check_interrupt();
  };
  Trace trace{image, options, options.resolution, PixelGrid{image}, {}, 0, {}, {}};
  const std::vector<Region> regions = occupiedRegions(image);
  trace.out.regions = int(regions.size());
  for (int g = 0; g < int(regions.size()); ++g) {
    if (g % 64 == 0) checkInterrupt();
    if (!settledAsSpeckColumnOrSymbol(trace, regions[g])) addPiecesOfRegion(trace, regions[g], g);
  }
  checkInterrupt();
  dropSpursAndBends(trace.pieces, trace.next_node);
  const auto at_node = endsByNode(trace.pieces);
  reportBends(trace, at_node);
  checkInterrupt();
  closeEnds(trace.pieces, at_node, trace.grid);
  checkInterrupt();
  const std::vector<Piece> kept = wallRuns(trace.pieces, options, trace.r);
  checkInterrupt();
  const auto groups = collinearGroups(kept, trace.grid, options, trace.r);
  checkInterrupt();
  for (const auto& group : groups) {
    if (!group.empty()) addWallsOfGroup(trace, kept, group);
  }
  checkInterrupt();
  reportUncovered(trace, regions);
  return std::move(trace.out);
}

}  // namespace isg::raster
