#include "slam/sgraph/plane_map.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace isg::slam {

namespace {

// The gap between two segments' projections onto a direction (negative when they overlap).
double gapAlong(const Eigen::Vector2d& direction, const Eigen::Vector2d& a0,
                const Eigen::Vector2d& a1, const Eigen::Vector2d& b0, const Eigen::Vector2d& b1) {
  const double a_lo = std::min(direction.dot(a0), direction.dot(a1));
  const double a_hi = std::max(direction.dot(a0), direction.dot(a1));
  const double b_lo = std::min(direction.dot(b0), direction.dot(b1));
  const double b_hi = std::max(direction.dot(b0), direction.dot(b1));
  return std::max(a_lo, b_lo) - std::min(a_hi, b_hi);
}

}  // namespace

Eigen::Vector2d alongWall(const bim::Plane& plane) {
  Eigen::Vector2d along(-plane.normal.y(), plane.normal.x());
  if (along.norm() < 1e-6) return Eigen::Vector2d::UnitX();
  return along.normalized();
}

std::pair<Eigen::Vector2d, Eigen::Vector2d> endsOnPlane(const MapPlane& plane) {
  const Eigen::Vector2d n = plane.plane.normal.head<2>();
  const double n2 = n.squaredNorm();
  if (n2 < 1e-12) return {plane.start, plane.end};  // a horizontal plane: no wall to lay them on
  const auto laid = [&](const Eigen::Vector2d& p) -> Eigen::Vector2d {
    return p - (n.dot(p) + plane.plane.d) / n2 * n;
  };
  return {laid(plane.start), laid(plane.end)};
}

PlaneObservation toMap(const PlaneObservation& o, const Eigen::Isometry3d& M_T_L) {
  PlaneObservation out = o;
  out.plane = o.plane.transformed(M_T_L);
  out.centroid = M_T_L * o.centroid;
  out.start = M_T_L * o.start;
  out.end = M_T_L * o.end;
  // The height range in M: the observation's corners at its lowest and highest points.
  const double z0 = (M_T_L * Eigen::Vector3d(o.start.x(), o.start.y(), o.z_min)).z();
  const double z1 = (M_T_L * Eigen::Vector3d(o.start.x(), o.start.y(), o.z_max)).z();
  out.z_min = std::min(z0, z1);
  out.z_max = std::max(z0, z1);
  return out;
}

void addHeights(MapPlane& plane, const PlaneObservation& o) {
  plane.z_min = std::min(plane.z_min, o.z_min);
  plane.z_max = std::max(plane.z_max, o.z_max);
  if (o.top == TopEdge::kSeen) plane.top_seen_z = std::min(plane.top_seen_z, o.z_max);
  if (o.top == TopEdge::kBeyondView) ++plane.tops_beyond_view;
}

void mergeHeights(MapPlane& kept, const MapPlane& dropped) {
  kept.z_min = std::min(kept.z_min, dropped.z_min);
  kept.z_max = std::max(kept.z_max, dropped.z_max);
  kept.top_seen_z = std::min(kept.top_seen_z, dropped.top_seen_z);
  kept.tops_beyond_view += dropped.tops_beyond_view;
}

bool seenAsWall(const MapPlane& plane, double min_height) {
  if (plane.z_max - plane.z_min >= min_height) return true;
  return plane.tops_beyond_view > 0 && plane.top_seen_z - plane.z_min >= min_height;
}

namespace {

// Whether an observation may join a map plane under its length bound: together they reach no
// farther than max_length, or the observation is centred on the plane's extent (it adds at most
// its own half beyond, which extend() does not take).
bool withinBound(const Eigen::Vector2d& along, const MapPlane& m, const PlaneObservation& o,
                 double max_length) {
  const double m_lo = std::min(along.dot(m.start), along.dot(m.end));
  const double m_hi = std::max(along.dot(m.start), along.dot(m.end));
  const double o_a = along.dot(o.start.head<2>()), o_b = along.dot(o.end.head<2>());
  const double reach = std::max({m_hi, o_a, o_b}) - std::min({m_lo, o_a, o_b});
  if (reach <= max_length) return true;
  const double centre = along.dot(o.centroid.head<2>());
  return centre >= m_lo && centre <= m_hi;
}

}  // namespace

void extend(MapPlane& m, const PlaneObservation& o, double max_length) {
  if (Eigen::Vector2d(m.plane.normal.y(), m.plane.normal.x()).norm() < 1e-6) return;
  const Eigen::Vector2d along = alongWall(m.plane);
  const double m_lo = std::min(along.dot(m.start), along.dot(m.end));
  const double m_hi = std::max(along.dot(m.start), along.dot(m.end));
  double lo = std::min({m_lo, along.dot(o.start.head<2>()), along.dot(o.end.head<2>())});
  double hi = std::max({m_hi, along.dot(o.start.head<2>()), along.dot(o.end.head<2>())});
  const double added = (m_lo - lo) + (hi - m_hi);
  if (max_length > 0.0 && hi - lo > max_length && added > 0.0) {
    const double room = std::max(0.0, max_length - (m_hi - m_lo));
    const double share = room / added;
    lo = m_lo - share * (m_lo - lo);
    hi = m_hi + share * (hi - m_hi);
  }
  const Eigen::Vector2d base = -m.plane.d * m.plane.normal.head<2>();
  const Eigen::Vector2d origin = base - along.dot(base) * along;
  m.start = origin + lo * along;
  m.end = origin + hi * along;
}

MapPlane newMapPlane(const PlaneObservation& o, double max_length) {
  MapPlane m;
  m.plane = o.plane;
  m.start = o.start.head<2>();
  m.end = o.end.head<2>();
  m.z_min = o.z_min;
  m.z_max = o.z_max;
  const double length = (m.end - m.start).norm();
  if (max_length > 0.0 && length > max_length) {
    const Eigen::Vector2d unit = (m.end - m.start) / length;
    // The centroid's place along the segment, kept within it.
    const double at = std::clamp(unit.dot(o.centroid.head<2>() - m.start), 0.5 * max_length,
                                 length - 0.5 * max_length);
    const Eigen::Vector2d centre = m.start + at * unit;
    m.start = centre - 0.5 * max_length * unit;
    m.end = centre + 0.5 * max_length * unit;
  }
  return m;
}

int associate(const PlaneObservation& o, const std::vector<MapPlane>& map,
              const AssociationOptions& options) {
  const double min_cos = std::cos(options.max_angle_deg * std::numbers::pi / 180.0);
  int best = -1;
  double best_distance = options.max_distance;
  for (int i = 0; i < int(map.size()); ++i) {
    const MapPlane& m = map[i];
    if (m.plane.normal.dot(o.plane.normal) < min_cos) continue;
    const double distance = std::abs(m.plane.signedDistance(o.centroid));
    if (distance > best_distance) continue;
    const Eigen::Vector2d along = alongWall(m.plane);
    const double gap = gapAlong(along, m.start, m.end, o.start.head<2>(), o.end.head<2>());
    if (gap > options.max_gap) continue;
    if (options.max_length > 0.0 && !withinBound(along, m, o, options.max_length)) continue;
    best = i;
    best_distance = distance;
  }
  return best;
}

}  // namespace isg::slam
