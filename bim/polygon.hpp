#pragma once

#include <Eigen/Core>
#include <optional>
#include <utility>
#include <vector>

namespace isg::bim {

using Polygon2 = std::vector<Eigen::Vector2d>;

// The z of the 3-D cross product of a and b: positive when b turns counter-clockwise from a.
inline double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Signed area (shoelace): positive for counter-clockwise vertex order.
double signedArea(const Polygon2& polygon);

// Area-weighted centroid of a simple polygon.
Eigen::Vector2d centroid(const Polygon2& polygon);

// Even-odd point-in-polygon test; points on the boundary count as inside.
bool containsPoint(const Polygon2& polygon, const Eigen::Vector2d& point);

// The first pair of edges (i, j) of a closed polygon that intersect although they are not
// neighbours, or that overlap when they are; nullopt for a simple polygon. Edge i runs from
// vertex i to vertex i+1 (mod n).
std::optional<std::pair<int, int>> findSelfIntersection(const Polygon2& polygon);

// Whether the closed segments [a0, a1] and [b0, b1] share a point.
bool segmentsIntersect(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1,
                       const Eigen::Vector2d& b0, const Eigen::Vector2d& b1);

// Distance from a point to the closed segment [a, b].
double distanceToSegment(const Eigen::Vector2d& point, const Eigen::Vector2d& a,
                         const Eigen::Vector2d& b);

}  // namespace isg::bim
