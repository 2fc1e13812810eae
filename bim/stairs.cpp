#include "bim/stairs.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace isg::bim {

std::vector<Eigen::Vector2d> StairGeometry::footprint() const {
  const Eigen::Vector2d half = 0.5 * stair->width * left_normal;
  const Eigen::Vector2d& a = stair->start;
  const Eigen::Vector2d b = stair->start + run * axis;
  return {a - half, b - half, b + half, a + half};
}

std::vector<Eigen::Vector2d> StairGeometry::openingFootprint() const {
  const double open = run * std::min(1.0, kStairHeadroom / rise());
  // [s0, s1] along the flight: at its `end` when it rises from start to end, else at its start.
  const double s0 = z_end >= z_start ? run - open : 0.0;
  const double s1 = z_end >= z_start ? run : open;
  const Eigen::Vector2d half = 0.5 * stair->width * left_normal;
  const Eigen::Vector2d a = stair->start + s0 * axis;
  const Eigen::Vector2d b = stair->start + s1 * axis;
  return {a - half, b - half, b + half, a + half};
}

bool StairGeometry::contains(const Eigen::Vector2d& point, double margin) const {
  const double s = along(point);
  const double t = across(point);
  return s >= -margin && s <= run + margin && std::abs(t) <= 0.5 * stair->width + margin;
}

double StairGeometry::walkLineZ(double s) const {
  const double u = std::clamp(s / run, 0.0, 1.0);
  return z_start + u * (z_end - z_start);
}

StairGeometry::Step StairGeometry::step(int k) const {
  // Each step's tread is at the height of the pitch line at the step's far edge: walking from
  // the lower end, step k rises by one step_rise; the last one is flush with the upper floor.
  const bool up = z_end >= z_start;
  const double s0 = k * going;
  const double s1 = (k + 1) * going;
  const double lower = std::min(z_start, z_end);
  const int from_bottom = up ? k + 1 : steps - k;
  return {s0, s1, lower + from_bottom * step_rise};
}

StairGeometry computeStairGeometry(const Stair& stair, const Level& from, const Level& to) {
  StairGeometry g;
  g.stair = &stair;
  const Eigen::Vector2d d = stair.end - stair.start;
  g.run = d.norm();
  g.axis = g.run > 0.0 ? Eigen::Vector2d(d / g.run) : Eigen::Vector2d::UnitX();
  g.left_normal = {-g.axis.y(), g.axis.x()};
  g.z_start = from.elevation;
  g.z_end = to.elevation;
  // The fewest equal steps of at most kMaxStepRise (a hair of tolerance so that 3.0 m / 0.2 m is
  // 15 steps, not 16).
  g.steps = std::max(1, static_cast<int>(std::ceil(g.rise() / kMaxStepRise - 1e-9)));
  g.step_rise = g.rise() / g.steps;
  g.going = g.run / g.steps;
  return g;
}

std::vector<Eigen::Vector2d> wallRectangle(const Wall& wall) {
  const Eigen::Vector2d d = wall.end - wall.start;
  const Eigen::Vector2d axis = d.normalized();
  const Eigen::Vector2d half = 0.5 * wall.thickness * Eigen::Vector2d(-axis.y(), axis.x());
  return {wall.start - half, wall.end - half, wall.end + half, wall.start + half};
}

namespace {

// The projections of a polygon on an axis.
std::pair<double, double> project(const std::vector<Eigen::Vector2d>& polygon,
                                  const Eigen::Vector2d& axis) {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (const auto& p : polygon) {
    const double v = p.dot(axis);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  return {lo, hi};
}

// Whether some edge normal of `edges_of` separates the two polygons (by more than -tolerance).
bool separatedByEdgeOf(const std::vector<Eigen::Vector2d>& edges_of,
                       const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b,
                       double tolerance) {
  for (std::size_t i = 0; i < edges_of.size(); ++i) {
    const Eigen::Vector2d edge = edges_of[(i + 1) % edges_of.size()] - edges_of[i];
    if (edge.norm() < 1e-12) continue;
    const Eigen::Vector2d normal = Eigen::Vector2d(-edge.y(), edge.x()).normalized();
    const auto [a_lo, a_hi] = project(a, normal);
    const auto [b_lo, b_hi] = project(b, normal);
    if (a_hi - b_lo <= tolerance || b_hi - a_lo <= tolerance) return true;
  }
  return false;
}

}  // namespace

bool convexPolygonsOverlap(const std::vector<Eigen::Vector2d>& a,
                           const std::vector<Eigen::Vector2d>& b, double tolerance) {
  // Separating axis theorem: convex polygons are disjoint iff an edge normal of one of them
  // separates them.
  return !separatedByEdgeOf(a, a, b, tolerance) && !separatedByEdgeOf(b, a, b, tolerance);
}

}  // namespace isg::bim
