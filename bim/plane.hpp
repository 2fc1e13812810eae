#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace isg::bim {

// A plane π = (n, d) with unit normal n and n·p + d = 0 for its points (docs/conventions.md). The
// one convention everywhere: plan surfaces, S-Graph planes and the factors between them.
struct Plane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double d = 0.0;

  // The plane through `point` with normal `normal` (normalised here).
  static Plane throughPoint(const Eigen::Vector3d& normal, const Eigen::Vector3d& point) {
    const Eigen::Vector3d n = normal.normalized();
    return {n, -n.dot(point)};
  }

  double signedDistance(const Eigen::Vector3d& point) const { return normal.dot(point) + d; }

  // The point of the plane closest to the origin of its frame: cp = -d·n.
  Eigen::Vector3d closestPoint() const { return -d * normal; }

  // The same plane expressed in another frame: for T = (R, t) mapping points of this plane's
  // frame into the target frame, n' = R n and d' = d - n'·t.
  Plane transformed(const Eigen::Isometry3d& T) const {
    const Eigen::Vector3d n = T.linear() * normal;
    return {n, d - n.dot(T.translation())};
  }

  // The same set of points with the opposite normal.
  Plane flipped() const { return {-normal, -d}; }
};

}  // namespace isg::bim
