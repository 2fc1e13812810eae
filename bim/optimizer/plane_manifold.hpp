#pragma once

#include <ceres/jet.h>
#include <ceres/manifold.h>

#include <Eigen/Core>
#include <cmath>

#include "bim/plane.hpp"

namespace isg::bim {

// Planes in the optimisation are 4-vectors [nx, ny, nz, d] (the convention of plane.hpp) updated
// through a minimal 3-parameter step (azimuth, elevation, distance).
//
// The step is taken in a frame attached to the current normal n: with u = ẑ × n / |ẑ × n| and
// v = n × u, a step (δa, δe, δd) gives n' = cos δe cos δa · n + cos δe sin δa · u + sin δe · v and
// d' = d + δd. For a vertical wall u is horizontal and v is ẑ, so δa and δe are exactly the
// change of the plane's azimuth and elevation; unlike global spherical angles the step has no
// singularity, even for horizontal planes (then u = x̂ × n). The S-Graph and the A-Graph share it.
class PlaneManifold : public ceres::Manifold {
 public:
  int AmbientSize() const override { return 4; }
  int TangentSize() const override { return 3; }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override;
  bool PlusJacobian(const double* x, double* jacobian) const override;
  bool Minus(const double* y, const double* x, double* y_minus_x) const override;
  bool MinusJacobian(const double* x, double* jacobian) const override;
};

// The tangent frame at normal n: u, v complete n to a right-handed orthonormal basis [n u v].
template <typename T>
void planeTangentFrame(const Eigen::Matrix<T, 3, 1>& n, Eigen::Matrix<T, 3, 1>& u,
                       Eigen::Matrix<T, 3, 1>& v) {
  using std::abs;
  using std::sqrt;
  // Use ẑ unless n is (nearly) vertical; then x̂. The switch is far from where it matters.
  const Eigen::Matrix<T, 3, 1> axis = abs(n.z()) < T(0.9)
                                          ? Eigen::Matrix<T, 3, 1>(T(0), T(0), T(1))
                                          : Eigen::Matrix<T, 3, 1>(T(1), T(0), T(0));
  u = axis.cross(n);
  u /= sqrt(u.squaredNorm());
  v = n.cross(u);
}

// y ⊖ x: the (azimuth, elevation, distance) step that takes plane x to plane y; templated so that
// AutoDiff cost functions can use it for their residuals (e.g. the S-Graph's (T⁻¹·π) ⊖ z).
template <typename T, typename U>
Eigen::Matrix<T, 3, 1> planeMinus(const Eigen::Matrix<T, 4, 1>& y,
                                  const Eigen::Matrix<U, 4, 1>& x) {
  using std::asin;
  using std::atan2;
  using std::sqrt;
  const Eigen::Matrix<U, 3, 1> nx = x.template head<3>() / sqrt(x.template head<3>().squaredNorm());
  Eigen::Matrix<U, 3, 1> u, v;
  planeTangentFrame(nx, u, v);
  const Eigen::Matrix<T, 3, 1> ny = y.template head<3>() / sqrt(y.template head<3>().squaredNorm());
  const T w0 = ny.dot(nx.template cast<T>());
  const T w1 = ny.dot(u.template cast<T>());
  T w2 = ny.dot(v.template cast<T>());
  if (w2 > T(1)) w2 = T(1);
  if (w2 < T(-1)) w2 = T(-1);
  Eigen::Matrix<T, 3, 1> out;
  out << atan2(w1, w0), asin(w2), y(3) - T(x(3));
  return out;
}

inline Eigen::Vector4d toVector(const Plane& plane) {
  return {plane.normal.x(), plane.normal.y(), plane.normal.z(), plane.d};
}

inline Plane toPlane(const Eigen::Vector4d& v) {
  const double norm = v.head<3>().norm();
  return {v.head<3>() / norm, v(3) / norm};
}

}  // namespace isg::bim
