#include "bim/optimizer/plane_manifold.hpp"

namespace isg::bim {

namespace {

using Vector3 = Eigen::Vector3d;

Vector3 unitNormal(const double* x) { return Eigen::Map<const Vector3>(x).normalized(); }

}  // namespace

bool PlaneManifold::Plus(const double* x, const double* delta, double* x_plus_delta) const {
  const Vector3 n = unitNormal(x);
  Vector3 u, v;
  planeTangentFrame(n, u, v);
  const double ca = std::cos(delta[0]), sa = std::sin(delta[0]);
  const double ce = std::cos(delta[1]), se = std::sin(delta[1]);
  const Vector3 moved = ce * ca * n + ce * sa * u + se * v;
  Eigen::Map<Vector3> normal_out(x_plus_delta);
  normal_out = moved;
  x_plus_delta[3] = x[3] + delta[2];
  return true;
}

bool PlaneManifold::PlusJacobian(const double* x, double* jacobian) const {
  const Vector3 n = unitNormal(x);
  Vector3 u, v;
  planeTangentFrame(n, u, v);
  // d(Plus)/dδ at δ = 0, 4 × 3 row-major: columns u, v for the normal, and 1 for the distance.
  Eigen::Map<Eigen::Matrix<double, 4, 3, Eigen::RowMajor>> J(jacobian);
  J.setZero();
  J.block<3, 1>(0, 0) = u;
  J.block<3, 1>(0, 1) = v;
  J(3, 2) = 1.0;
  return true;
}

bool PlaneManifold::Minus(const double* y, const double* x, double* y_minus_x) const {
  const Eigen::Vector4d xv = Eigen::Map<const Eigen::Vector4d>(x);
  const Eigen::Vector4d yv = Eigen::Map<const Eigen::Vector4d>(y);
  Eigen::Map<Vector3> out(y_minus_x);
  out = planeMinus<double, double>(yv, xv);
  return true;
}

bool PlaneManifold::MinusJacobian(const double* x, double* jacobian) const {
  const Vector3 n = unitNormal(x);
  Vector3 u, v;
  planeTangentFrame(n, u, v);
  // d(y ⊖ x)/dy at y = x, 3 × 4 row-major. The normal of y is normalised inside Minus, so the
  // derivative with respect to y's (unnormalised) normal is projected by 1/|n|.
  const double scale = 1.0 / Eigen::Map<const Vector3>(x).norm();
  Eigen::Map<Eigen::Matrix<double, 3, 4, Eigen::RowMajor>> J(jacobian);
  J.setZero();
  J.block<1, 3>(0, 0) = scale * u.transpose();
  J.block<1, 3>(1, 0) = scale * v.transpose();
  J(2, 3) = 1.0;
  return true;
}

}  // namespace isg::bim
