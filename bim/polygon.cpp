#include "bim/polygon.hpp"

#include <algorithm>
#include <cmath>

#include "bim/box_grid.hpp"

namespace isg::bim {

namespace {

// Orientation of c relative to the directed line a → b, with a tolerance scaled to the segment.
int orientation(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const double value = cross(b - a, c - a);
  const double scale = std::max({1.0, (b - a).norm(), (c - a).norm()});
  const double eps = 1e-12 * scale * scale;
  return value > eps ? 1 : (value < -eps ? -1 : 0);
}

bool onSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  const double eps = 1e-12;
  return p.x() <= std::max(a.x(), b.x()) + eps && p.x() >= std::min(a.x(), b.x()) - eps &&
         p.y() <= std::max(a.y(), b.y()) + eps && p.y() >= std::min(a.y(), b.y()) - eps;
}

}  // namespace

// Both sum cross products of vertices taken relative to the first: from B's origin they would be
// products of coordinates in the kilometres that cancel to an area of square metres, and lose
// six digits at 8 km (docs/conventions.md, "Where B's origin is").
double signedArea(const Polygon2& polygon) {
  if (polygon.empty()) return 0.0;
  const Eigen::Vector2d& origin = polygon[0];
  double twice = 0.0;
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
    twice += cross(polygon[i] - origin, polygon[i + 1] - origin);
  }
  return 0.5 * twice;
}

Eigen::Vector2d centroid(const Polygon2& polygon) {
  const double area = signedArea(polygon);
  if (std::abs(area) < 1e-12) {
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const auto& p : polygon) mean += p;
    return polygon.empty() ? mean : Eigen::Vector2d(mean / double(polygon.size()));
  }
  const Eigen::Vector2d& origin = polygon[0];
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
    const Eigen::Vector2d p = polygon[i] - origin, q = polygon[i + 1] - origin;
    sum += (p + q) * cross(p, q);
  }
  return origin + sum / (6.0 * area);
}

double distanceToSegment(const Eigen::Vector2d& point, const Eigen::Vector2d& a,
                         const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((point - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (a + t * ab - point).norm();
}

bool containsPoint(const Polygon2& polygon, const Eigen::Vector2d& point) {
  bool inside = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const auto& a = polygon[i];
    const auto& b = polygon[j];
    if (distanceToSegment(point, a, b) < 1e-9) return true;
    if ((a.y() > point.y()) != (b.y() > point.y())) {
      const double x = a.x() + (point.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (point.x() < x) inside = !inside;
    }
  }
  return inside;
}

bool segmentsIntersect(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1,
                       const Eigen::Vector2d& b0, const Eigen::Vector2d& b1) {
  const int o1 = orientation(a0, a1, b0);
  const int o2 = orientation(a0, a1, b1);
  const int o3 = orientation(b0, b1, a0);
  const int o4 = orientation(b0, b1, a1);
  if (o1 != o2 && o3 != o4) return true;
  if (o1 == 0 && onSegment(a0, a1, b0)) return true;
  if (o2 == 0 && onSegment(a0, a1, b1)) return true;
  if (o3 == 0 && onSegment(b0, b1, a0)) return true;
  if (o4 == 0 && onSegment(b0, b1, a1)) return true;
  return false;
}

std::optional<std::pair<int, int>> findSelfIntersection(const Polygon2& polygon) {
  const int n = static_cast<int>(polygon.size());
  auto vertex = [&](int i) -> const Eigen::Vector2d& { return polygon[((i % n) + n) % n]; };
  // Edge pairs come from a grid over the edges' boxes (grown by the intersection tests'
  // tolerance), so a simple outline of 10^5 vertices is checked in near-linear time.
  std::vector<Box2> boxes;
  boxes.reserve(polygon.size());
  for (int i = 0; i < n; ++i) {
    const Box2 box = Box2::around(vertex(i), vertex(i + 1));
    boxes.push_back(box.grown(1e-9 * std::max(1.0, (box.hi - box.lo).maxCoeff())));
  }
  const BoxGrid grid(std::move(boxes));
  for (int i = 0; i < n; ++i) {
    for (int j : grid.candidates(grid.box(i))) {
      if (j <= i) continue;
      const bool neighbours = (j == i + 1) || (i == 0 && j == n - 1);
      if (neighbours) {
        // Neighbours share a vertex; they are only wrong when they fold back onto each other.
        const int shared = (j == i + 1) ? j : i;
        const Eigen::Vector2d u = vertex(shared - 1) - vertex(shared);
        const Eigen::Vector2d v = vertex(shared + 1) - vertex(shared);
        if (std::abs(cross(u, v)) <= 1e-12 * std::max(1.0, u.norm() * v.norm()) && u.dot(v) > 0) {
          return std::make_pair(i, j);
        }
        continue;
      }
      if (segmentsIntersect(vertex(i), vertex(i + 1), vertex(j), vertex(j + 1))) {
        return std::make_pair(i, j);
      }
    }
  }
  return std::nullopt;
}

}  // namespace isg::bim
