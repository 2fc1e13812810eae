#include "ifc/mesh_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include "bim/polygon.hpp"

namespace isg::ifc {
namespace {

using Vec2 = Eigen::Vector2d;

double cross(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// Andrew's monotone chain; counter-clockwise, without collinear points.
std::vector<Vec2> convexHull(std::vector<Vec2> points) {
  std::sort(points.begin(), points.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  std::vector<Vec2> hull(2 * points.size());
  std::size_t k = 0;
  for (const auto& p : points) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p) <= 0) --k;
    hull[k++] = p;
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

struct Rectangle {
  Vec2 u = Vec2::UnitX();  // unit direction of the first side
  double u_min = 0, u_max = 0, v_min = 0, v_max = 0;
  double area() const { return (u_max - u_min) * (v_max - v_min); }
};

Rectangle rectangleAlong(const std::vector<Vec2>& points, const Vec2& u) {
  const Vec2 v(-u.y(), u.x());
  Rectangle r;
  r.u = u;
  r.u_min = r.v_min = std::numeric_limits<double>::infinity();
  r.u_max = r.v_max = -std::numeric_limits<double>::infinity();
  for (const auto& p : points) {
    r.u_min = std::min(r.u_min, p.dot(u));
    r.u_max = std::max(r.u_max, p.dot(u));
    r.v_min = std::min(r.v_min, p.dot(v));
    r.v_max = std::max(r.v_max, p.dot(v));
  }
  return r;
}

Eigen::Vector3d faceNormal(const Face& face) {
  // Newell's method: right for any planar polygon, convex or not.
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < face.size(); ++i) {
    const auto& a = face[i];
    const auto& b = face[(i + 1) % face.size()];
    n += Eigen::Vector3d((a.y() - b.y()) * (a.z() + b.z()), (a.z() - b.z()) * (a.x() + b.x()),
                         (a.x() - b.x()) * (a.y() + b.y()));
  }
  return n * 0.5;  // its length is the face's area
}

}  // namespace

std::optional<Bounds> boundsOf(const Mesh& body) {
  Bounds b;
  b.min.setConstant(std::numeric_limits<double>::infinity());
  b.max.setConstant(-std::numeric_limits<double>::infinity());
  bool any = false;
  for (const auto& face : body) {
    for (const auto& p : face) {
      b.min = b.min.cwiseMin(p);
      b.max = b.max.cwiseMax(p);
      any = true;
    }
  }
  if (!any) return std::nullopt;
  return b;
}

namespace {

// The smallest rectangle about the hull (it has a side along an edge of the hull), or the one
// along `preferred_axis` when that is within 2 % of it; its u along the long side unless the
// preferred direction was kept.
Rectangle wallRectangle(const std::vector<Vec2>& hull, const Eigen::Vector2d& preferred_axis) {
  Rectangle best;
  double best_area = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Vec2 edge = hull[(i + 1) % hull.size()] - hull[i];
    if (edge.norm() < 1e-12) continue;
    const Rectangle r = rectangleAlong(hull, edge.normalized());
    if (r.area() < best_area) best_area = r.area(), best = r;
  }
  if (preferred_axis.norm() > 1e-9) {
    const Rectangle r = rectangleAlong(hull, preferred_axis.normalized());
    if (r.area() <= best_area * 1.02 + 1e-9) best = r;
  }
  const bool kept_preferred = preferred_axis.norm() > 1e-9 &&
                              best.u.dot(preferred_axis) / preferred_axis.norm() > 1.0 - 1e-12;
  if (!kept_preferred && best.v_max - best.v_min > best.u_max - best.u_min) {
    const Vec2 u(-best.u.y(), best.u.x());  // the long side's direction
    best = rectangleAlong(hull, u);
  }
  return best;
}

// Where vertical planes across the wall at stations along it cut the faces' edges: per
// station, the highest and lowest z and the span across the wall.
struct Sections {
  std::vector<double> stations;
  std::vector<double> top, bottom, across_min, across_max;
};

Sections sectionsOf(const Mesh& body, const Rectangle& best) {
  const Vec2 u = best.u;
  const Vec2 v(-u.y(), u.x());
  const double length = best.u_max - best.u_min;
  const double inset = std::min(0.02, length / 4);
  const int stations = std::clamp(static_cast<int>(std::ceil(length / 0.05)), 8, 400);
  const double inf = std::numeric_limits<double>::infinity();
  Sections s{{},
             std::vector<double>(stations, -inf),
             std::vector<double>(stations, inf),
             std::vector<double>(stations, inf),
             std::vector<double>(stations, -inf)};
  for (int k = 0; k < stations; ++k) {
    s.stations.push_back(best.u_min + inset + (length - 2 * inset) * k / double(stations - 1));
  }
  for (const auto& face : body) {
    double f_min = inf, f_max = -inf;
    for (const auto& p : face) {
      const double t = p.head<2>().dot(u);
      f_min = std::min(f_min, t), f_max = std::max(f_max, t);
    }
    for (int k = 0; k < stations; ++k) {
      const double t = s.stations[k];
      if (t < f_min || t > f_max) continue;
      for (std::size_t i = 0; i < face.size(); ++i) {
        const auto& a = face[i];
        const auto& b = face[(i + 1) % face.size()];
        const double ta = a.head<2>().dot(u), tb = b.head<2>().dot(u);
        if ((ta - t) * (tb - t) > 0) continue;
        double z_lo, z_hi, v_lo, v_hi;
        const double va = a.head<2>().dot(v), vb = b.head<2>().dot(v);
        if (std::abs(tb - ta) < 1e-12) {
          z_lo = std::min(a.z(), b.z()), z_hi = std::max(a.z(), b.z());
          v_lo = std::min(va, vb), v_hi = std::max(va, vb);
        } else {
          const double f = (t - ta) / (tb - ta);
          z_lo = z_hi = a.z() + (b.z() - a.z()) * f;
          v_lo = v_hi = va + (vb - va) * f;
        }
        s.across_min[k] = std::min(s.across_min[k], v_lo);
        s.across_max[k] = std::max(s.across_max[k], v_hi);
        s.top[k] = std::max(s.top[k], z_hi);
        s.bottom[k] = std::min(s.bottom[k], z_lo);
      }
    }
  }
  return s;
}

// How straight the wall is: its narrowest section over its thickness (away from its ends) for a
// long wall, from how much of its rectangle it fills for a short one.
double straightnessOf(const WallFit& fit, const Rectangle& best, const Sections& s) {
  const double length = best.u_max - best.u_min;
  const double inf = std::numeric_limits<double>::infinity();
  if (length > 3 * fit.thickness) {
    double narrowest = inf;
    for (std::size_t k = 0; k < s.stations.size(); ++k) {
      const double t = s.stations[k];
      if (t < best.u_min + fit.thickness || t > best.u_max - fit.thickness) continue;
      narrowest = std::min(narrowest, std::max(0.0, s.across_max[k] - s.across_min[k]));
    }
    return narrowest < inf ? narrowest / fit.thickness : fit.straightness;
  }
  if (length > 0) {
    const double least_fill = 1.0 - std::min(fit.thickness, length) / length;
    return least_fill > 0 ? std::min(1.0, fit.rectangle_fill / least_fill) : fit.rectangle_fill;
  }
  return fit.straightness;
}

}  // namespace

std::optional<WallFit> fitWall(const Mesh& body, const Eigen::Vector2d& preferred_axis) {
  std::vector<Vec2> points;
  for (const auto& face : body) {
    for (const auto& p : face) points.push_back(p.head<2>());
  }
  const std::vector<Vec2> hull = convexHull(points);
  if (hull.size() < 3) return std::nullopt;
  const Rectangle best = wallRectangle(hull, preferred_axis);
  const Vec2 u = best.u;
  const Vec2 v(-u.y(), u.x());
  const double mid_v = 0.5 * (best.v_min + best.v_max);
  WallFit fit;
  fit.start = u * best.u_min + v * mid_v;
  fit.end = u * best.u_max + v * mid_v;
  fit.thickness = best.v_max - best.v_min;
  // Footprint over rectangle: a closed body's faces seen from above cover its footprint twice
  // (once from the top, once from the bottom), whichever way a tool turned their normals.
  double projected_area = 0.0;
  for (const auto& face : body) projected_area += std::abs(faceNormal(face).z());
  fit.rectangle_fill = best.area() > 0 ? std::min(1.0, 0.5 * projected_area / best.area()) : 0.0;
  // Top and bottom along the axis: where a vertical plane across the wall at each station cuts
  // the faces' edges.
  const Sections sections = sectionsOf(body, best);
  fit.straightness = straightnessOf(fit, best, sections);
  std::vector<double> tops, bottoms;
  for (std::size_t k = 0; k < sections.stations.size(); ++k) {
    if (sections.top[k] > sections.bottom[k]) {
      tops.push_back(sections.top[k]), bottoms.push_back(sections.bottom[k]);
    }
  }
  if (tops.empty()) return std::nullopt;
  fit.top = *std::min_element(tops.begin(), tops.end());
  fit.highest_top = *std::max_element(tops.begin(), tops.end());
  fit.lowest_bottom = *std::min_element(bottoms.begin(), bottoms.end());
  std::nth_element(bottoms.begin(), bottoms.begin() + bottoms.size() / 2, bottoms.end());
  fit.bottom = bottoms[bottoms.size() / 2];
  return fit;
}

std::optional<FlightFit> fitFlight(const Mesh& body) {
  const auto rectangle = fitWall(body, Eigen::Vector2d::Zero());
  if (!rectangle) return std::nullopt;
  const Vec2 long_side = (rectangle->end - rectangle->start).normalized();
  const Vec2 centre = 0.5 * (rectangle->start + rectangle->end);
  const double half_length = 0.5 * (rectangle->end - rectangle->start).norm();
  const double half_width = 0.5 * rectangle->thickness;
  // How much higher the body's top is at the +direction end than at the −direction end: the
  // highest vertex within the outer quarter of each end.
  auto rise = [&](const Vec2& direction, double half_extent) {
    const double inf = std::numeric_limits<double>::infinity();
    double top_minus = -inf, top_plus = -inf;
    for (const auto& face : body) {
      for (const auto& p : face) {
        const double t = (p.head<2>() - centre).dot(direction);
        if (t <= -0.5 * half_extent) top_minus = std::max(top_minus, p.z());
        if (t >= 0.5 * half_extent) top_plus = std::max(top_plus, p.z());
      }
    }
    return top_plus - top_minus;
  };
  const Vec2 across(-long_side.y(), long_side.x());
  const double rise_long = rise(long_side, half_length);
  const double rise_across = rise(across, half_width);
  const bool along_long = std::abs(rise_long) >= std::abs(rise_across);
  Vec2 up = along_long ? long_side : across;
  if ((along_long ? rise_long : rise_across) < 0) up = -up;
  const double half_run = along_long ? half_length : half_width;
  FlightFit fit;
  fit.low_edge = centre - half_run * up;
  fit.high_edge = centre + half_run * up;
  fit.width = 2.0 * (along_long ? half_width : half_length);
  fit.bottom = std::numeric_limits<double>::infinity();
  fit.top = -fit.bottom;
  for (const auto& face : body) {
    for (const auto& p : face) {
      fit.bottom = std::min(fit.bottom, p.z());
      fit.top = std::max(fit.top, p.z());
    }
  }
  return fit;
}

std::optional<AxisExtent> extentAlong(const Mesh& body, const Eigen::Vector2d& start,
                                      const Eigen::Vector2d& end) {
  const Vec2 axis = end - start;
  if (axis.norm() < 1e-9) return std::nullopt;
  const Vec2 u = axis.normalized();
  const auto bounds = boundsOf(body);
  if (!bounds) return std::nullopt;
  AxisExtent e;
  e.along_min = std::numeric_limits<double>::infinity();
  e.along_max = -e.along_min;
  for (const auto& face : body) {
    for (const auto& p : face) {
      const double t = (p.head<2>() - start).dot(u);
      e.along_min = std::min(e.along_min, t);
      e.along_max = std::max(e.along_max, t);
    }
  }
  e.z_min = bounds->min.z();
  e.z_max = bounds->max.z();
  return e;
}

namespace {

// Vertices welded to the millimetre: a key per vertex.
using Key = std::pair<long long, long long>;
using Edge = std::pair<Key, Key>;

Key keyOf(const Eigen::Vector3d& p) {
  return Key{std::llround(p.x() * 1000.0), std::llround(p.y() * 1000.0)};
}

// The edges of the body's downward faces at its bottom (within 2 cm of z0), seen from above
// counter-clockwise, and each welded vertex's position.
std::vector<Edge> bottomEdges(const Mesh& body, double z0, std::map<Key, Vec2>& position) {
  std::vector<Edge> directed;
  for (const auto& face : body) {
    if (face.size() < 3) continue;
    const Eigen::Vector3d n = faceNormal(face);
    if (n.norm() < 1e-12 || n.z() > -0.99 * n.norm()) continue;  // not facing down
    bool low = true;
    for (const auto& p : face) low = low && p.z() < z0 + 0.02;
    if (!low) continue;
    // Seen from above a downward face runs clockwise: reversed, every loop comes out CCW.
    for (std::size_t i = 0; i < face.size(); ++i) {
      const auto& from = face[(i + 1) % face.size()];
      const auto& to = face[i];
      const Key a = keyOf(from), b = keyOf(to);
      if (a == b) continue;
      position.emplace(a, from.head<2>());
      position.emplace(b, to.head<2>());
      directed.emplace_back(a, b);
    }
  }
  return directed;
}

// An edge with another face's vertex on it (a T-junction: one long side against two short ones)
// split there, so that shared sides cancel whatever way the faces were cut. Bounded: beyond
// 4 million edge-vertex pairs the faces are taken as they are.
std::vector<Edge> splitAtJunctions(const std::vector<Edge>& directed,
                                   std::map<Key, Vec2>& position) {
  if (directed.size() * position.size() > 4'000'000) return directed;
  std::vector<Edge> split;
  for (const auto& [a, b] : directed) {
    const Vec2 pa = position[a], pb = position[b];
    const Vec2 d = pb - pa;
    const double length = d.norm();
    std::vector<std::pair<double, Key>> inner;
    for (const auto& [key, p] : position) {
      if (key == a || key == b) continue;
      const double t = (p - pa).dot(d) / (length * length);
      if (t <= 0 || t >= 1) continue;
      if (bim::distanceToSegment(p, pa, pb) < 1e-3) inner.emplace_back(t, key);
    }
    std::sort(inner.begin(), inner.end());
    Key from = a;
    for (const auto& [t, key] : inner) {
      split.emplace_back(from, key);
      from = key;
    }
    split.emplace_back(from, b);
  }
  return split;
}

// The boundary edges chained into closed loops (an edge and its reversed twin cancel).
std::vector<std::vector<Vec2>> loopsOf(const std::vector<Edge>& split,
                                       std::map<Key, Vec2>& position) {
  std::map<Edge, int> edges;  // directed edge → count
  for (const auto& [a, b] : split) {
    auto twin = edges.find({b, a});
    if (twin != edges.end()) {
      if (--twin->second == 0) edges.erase(twin);
    } else {
      ++edges[{a, b}];
    }
  }
  std::multimap<Key, Key> next;
  for (const auto& [edge, count] : edges) {
    for (int i = 0; i < count; ++i) next.emplace(edge.first, edge.second);
  }
  std::vector<std::vector<Vec2>> loops;
  while (!next.empty()) {
    auto it = next.begin();
    const Key first = it->first;
    Key at = it->second;
    next.erase(it);
    std::vector<Vec2> loop{position[first]};
    bool closed = false;
    for (std::size_t guard = 0; guard <= edges.size() + 1; ++guard) {
      if (at == first) {
        closed = true;
        break;
      }
      loop.push_back(position[at]);
      auto step = next.find(at);
      if (step == next.end()) break;
      at = step->second;
      next.erase(step);
    }
    if (closed && loop.size() >= 3) loops.push_back(std::move(loop));
  }
  return loops;
}

// Collinear vertices (within 1 mm of the line through their neighbours) removed; counter-clockwise.
std::vector<Vec2> simplifiedOutline(std::vector<Vec2> outline) {
  for (bool removed = true; removed && outline.size() > 3;) {
    removed = false;
    for (std::size_t i = 0; i < outline.size() && outline.size() > 3; ++i) {
      const Vec2& prev = outline[(i + outline.size() - 1) % outline.size()];
      const Vec2& next_vertex = outline[(i + 1) % outline.size()];
      if (bim::distanceToSegment(outline[i], prev, next_vertex) < 1e-3) {
        outline.erase(outline.begin() + static_cast<long>(i));
        removed = true;
      }
    }
  }
  if (bim::signedArea(outline) < 0) std::reverse(outline.begin(), outline.end());
  return outline;
}

}  // namespace

std::optional<Footprint> footprintOf(const Mesh& body) {
  const auto bounds = boundsOf(body);
  if (!bounds) return std::nullopt;
  const double z0 = bounds->min.z();
  std::map<Key, Vec2> position;
  const std::vector<Edge> directed = bottomEdges(body, z0, position);
  const std::vector<std::vector<Vec2>> loops =
      loopsOf(splitAtJunctions(directed, position), position);
  if (loops.empty()) return std::nullopt;
  std::size_t largest = 0;
  for (std::size_t i = 1; i < loops.size(); ++i) {
    if (std::abs(bim::signedArea(loops[i])) > std::abs(bim::signedArea(loops[largest]))) {
      largest = i;
    }
  }
  Footprint footprint;
  footprint.outline = simplifiedOutline(loops[largest]);
  footprint.z = z0;
  footprint.loops = static_cast<int>(loops.size());
  return footprint;
}

}  // namespace isg::ifc
