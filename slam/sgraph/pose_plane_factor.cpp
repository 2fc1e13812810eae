#include <algorithm>
#include <cmath>

#include "slam/sgraph/sgraph_factors.hpp"

namespace isg::slam {
namespace {

Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return m;
}

}  // namespace

PosePlaneFactor::PosePlaneFactor(const Eigen::Vector4d& measured, const Eigen::Isometry3d& R_T_L,
                                 double sigma_angle, double sigma_distance)
    : measured_distance_(measured(3)),
      measured_normal_(measured.head<3>() / std::sqrt(measured.head<3>().squaredNorm())),
      R_T_L_rotation_(R_T_L.rotation()),
      R_T_L_translation_(R_T_L.translation()),
      weights_(1.0 / sigma_angle, 1.0 / sigma_angle, 1.0 / sigma_distance) {
  bim::planeTangentFrame(measured_normal_, tangent_u_, tangent_v_);
}

bool PosePlaneFactor::Evaluate(double const* const* parameters, double* residuals,
                               double** jacobians) const {
  const Eigen::Map<const Eigen::Vector3d> p(parameters[0]);
  const Eigen::Map<const Eigen::Quaterniond> q(parameters[1]);
  const double* plane = parameters[2];
  // The residual, as bim::planeMinus computes it.
  const Eigen::Matrix3d R_q = q.toRotationMatrix();
  const Eigen::Matrix3d R = R_q * R_T_L_rotation_;
  const Eigen::Vector3d arm = q * R_T_L_translation_;  // the LiDAR from the base, in M
  const Eigen::Vector3d t = arm + p;
  const Eigen::Vector3d n(plane[0], plane[1], plane[2]);
  const Eigen::Vector3d m = R.transpose() * n;  // the predicted normal, not unit
  const double predicted_distance = plane[3] + n.dot(t);
  const double norm = std::sqrt(m.squaredNorm());
  const Eigen::Vector3d ny = m / norm;
  const double w0 = ny.dot(measured_normal_);
  const double w1 = ny.dot(tangent_u_);
  double w2 = ny.dot(tangent_v_);
  // At ±1 (a plane seen edge-on to its measurement) asin has no finite slope: none is given.
  const bool clamped = w2 >= 1.0 || w2 <= -1.0;
  w2 = std::clamp(w2, -1.0, 1.0);
  residuals[0] = weights_(0) * std::atan2(w1, w0);
  residuals[1] = weights_(1) * std::asin(w2);
  residuals[2] = weights_(2) * (predicted_distance - measured_distance_);
  if (!jacobians) return true;

  // The angle rows through the predicted normal m: d(ny)/dm = (I − ny nyᵀ) / |m|.
  const Eigen::Matrix3d unit_of_m = (Eigen::Matrix3d::Identity() - ny * ny.transpose()) / norm;
  const Eigen::RowVector3d dw0 = measured_normal_.transpose() * unit_of_m;
  const Eigen::RowVector3d dw1 = tangent_u_.transpose() * unit_of_m;
  const Eigen::RowVector3d dw2 = tangent_v_.transpose() * unit_of_m;
  Eigen::Matrix<double, 2, 3> angle_by_m;
  angle_by_m.row(0) = weights_(0) * (w0 * dw1 - w1 * dw0) / (w0 * w0 + w1 * w1);
  angle_by_m.row(1) = clamped ? Eigen::RowVector3d::Zero()
                              : Eigen::RowVector3d(weights_(1) * dw2 / std::sqrt(1.0 - w2 * w2));

  if (jacobians[0]) {  // position: the distance row only
    Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> J(jacobians[0]);
    J.topRows<2>().setZero();
    J.row(2) = weights_(2) * n.transpose();
  }
  if (jacobians[1]) {
    // ceres::EigenQuaternionManifold: q ⊕ δ = [cos|δ|, sin|δ| δ/|δ|] · q, a turn by 2δ on the
    // left, so d(R_qᵀ n)/dδ = 2 R_qᵀ [n]× and d(R_q b)/dδ = −2 [R_q b]×. The ambient Jacobian
    // J_δ · Pᵀ, with P the manifold's (orthonormal) plus-Jacobian, gives J_δ through it.
    Eigen::Matrix3d by_turn;
    by_turn.topRows<2>() =
        angle_by_m * R_T_L_rotation_.transpose() * (2.0 * R_q.transpose() * skew(n));
    by_turn.row(2) = weights_(2) * n.transpose() * (-2.0 * skew(arm));
    Eigen::Matrix<double, 4, 3> plus;  // rows x, y, z, w
    plus.topRows<3>() = q.w() * Eigen::Matrix3d::Identity() - skew(q.vec());
    plus.row(3) = -q.vec().transpose();
    Eigen::Map<Eigen::Matrix<double, 3, 4, Eigen::RowMajor>> J(jacobians[1]);
    J = by_turn * plus.transpose();
  }
  if (jacobians[2]) {
    Eigen::Map<Eigen::Matrix<double, 3, 4, Eigen::RowMajor>> J(jacobians[2]);
    J.topLeftCorner<2, 3>() = angle_by_m * R.transpose();
    J.topRightCorner<2, 1>().setZero();
    J.block<1, 3>(2, 0) = weights_(2) * t.transpose();
    J(2, 3) = weights_(2);
  }
  return true;
}

}  // namespace isg::slam
