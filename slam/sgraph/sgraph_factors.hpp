#pragma once

#include <ceres/autodiff_cost_function.h>
#include <ceres/rotation.h>
#include <ceres/sized_cost_function.h>

#include <Eigen/Geometry>

#include "bim/optimizer/plane_manifold.hpp"

namespace isg::slam {

// The S-Graph's keyframe factors (docs/slam.md), as Ceres AutoDiff cost functions but for the
// plane observation, whose Jacobians are written by hand. A keyframe pose M_T_R is two parameter
// blocks: its position (3) and its orientation as an Eigen quaternion [x, y, z, w] (4, on
// ceres::EigenQuaternionManifold). Planes are [n, d] on bim::PlaneManifold.
// The room factors are the A-Graph's (bim/optimizer/agraph_factors.hpp): the same maths, written
// once.

// A plane observed in the LiDAR frame of a keyframe: e = (M_T_L⁻¹ · π_M) ⊖ z in the minimal
// (azimuth, elevation, distance) form, whitened. M_T_L = M_T_R · R_T_L.
// For T = (R, t), T⁻¹ · π = (Rᵀn, d + n·t).
// Parameters: position (3), orientation (4, Eigen quaternion), π_M (4). Its Jacobians are written
// by hand (slam/sgraph/pose_plane_factor.cpp): it is most of the window optimisation's residuals,
// and with AutoDiff's 11-wide dual numbers it was a sixth of a run's CPU (perf, D6 as built).
// The residual is computed by the same steps as before (equal to rounding: Eigen vectorises
// doubles, not dual numbers).
class PosePlaneFactor : public ceres::SizedCostFunction<3, 3, 4, 4> {
 public:
  PosePlaneFactor(const Eigen::Vector4d& measured, const Eigen::Isometry3d& R_T_L,
                  double sigma_angle, double sigma_distance);

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

  static ceres::CostFunction* create(const Eigen::Vector4d& measured,
                                     const Eigen::Isometry3d& R_T_L, double sigma_angle,
                                     double sigma_distance) {
    return new PosePlaneFactor(measured, R_T_L, sigma_angle, sigma_distance);
  }

 private:
  double measured_distance_;
  // The measured plane's unit normal and its tangent frame (bim::planeMinus's x, u, v).
  Eigen::Vector3d measured_normal_, tangent_u_, tangent_v_;
  Eigen::Matrix3d R_T_L_rotation_;
  Eigen::Vector3d R_T_L_translation_;
  Eigen::Vector3d weights_;
};

// Odometry between two keyframes: the measured relative pose Δ = M_T_Ri⁻¹ · M_T_Rj against the
// estimated one; residual [translation error (3), 2·vec(q_error) (3)], whitened per component.
struct OdometryFactor {
  OdometryFactor(const Eigen::Isometry3d& measured, double sigma_translation, double sigma_rotation)
      : dq_(measured.rotation()),
        dt_(measured.translation()),
        weight_t_(1.0 / sigma_translation),
        weight_r_(1.0 / sigma_rotation) {}

  template <typename T>
  bool operator()(const T* p_i, const T* q_i, const T* p_j, const T* q_j, T* residual) const {
    const Eigen::Map<const Eigen::Quaternion<T>> qi(q_i), qj(q_j);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> pi(p_i), pj(p_j);
    const Eigen::Quaternion<T> qi_inverse = qi.conjugate();
    const Eigen::Matrix<T, 3, 1> estimated_t = qi_inverse * (pj - pi);
    const Eigen::Quaternion<T> estimated_q = qi_inverse * qj;
    const Eigen::Quaternion<T> error_q = dq_.cast<T>().conjugate() * estimated_q;
    const Eigen::Matrix<T, 3, 1> error_t = estimated_t - dt_.cast<T>();
    for (int k = 0; k < 3; ++k) {
      residual[k] = T(weight_t_) * error_t(k);
      residual[3 + k] = T(weight_r_) * T(2.0) * error_q.vec()(k);
    }
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Isometry3d& measured, double sigma_translation,
                                     double sigma_rotation) {
    return new ceres::AutoDiffCostFunction<OdometryFactor, 6, 3, 4, 3, 4>(
        new OdometryFactor(measured, sigma_translation, sigma_rotation));
  }

 private:
  Eigen::Quaterniond dq_;
  Eigen::Vector3d dt_;
  double weight_t_, weight_r_;
};

// Gravity on one keyframe: its up (q⁻¹ · z, M's z in R) against the up the IMU measured, in R;
// three residuals of rank two (a turn about up changes neither), whitened by σ in radians.
struct GravityFactor {
  GravityFactor(const Eigen::Vector3d& measured_up, double sigma)
      : up_(measured_up.normalized()), weight_(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* q, T* residual) const {
    const Eigen::Map<const Eigen::Quaternion<T>> M_q_R(q);
    const Eigen::Matrix<T, 3, 1> estimated = M_q_R.conjugate() * Eigen::Matrix<T, 3, 1>::UnitZ();
    for (int k = 0; k < 3; ++k) residual[k] = T(weight_) * (estimated(k) - T(up_(k)));
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Vector3d& measured_up, double sigma) {
    return new ceres::AutoDiffCostFunction<GravityFactor, 3, 4>(
        new GravityFactor(measured_up, sigma));
  }

 private:
  Eigen::Vector3d up_;
  double weight_;
};

// A keyframe's height in M against the height it should have (its floor's): one residual,
// whitened by σ in metres.
struct HeightFactor {
  HeightFactor(double height, double sigma) : height_(height), weight_(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* position, T* residual) const {
    residual[0] = T(weight_) * (position[2] - T(height_));
    return true;
  }

  static ceres::CostFunction* create(double height, double sigma) {
    return new ceres::AutoDiffCostFunction<HeightFactor, 1, 3>(new HeightFactor(height, sigma));
  }

 private:
  double height_, weight_;
};

// LiDAR odometry between two keyframes (slam/sgraph/scan_registration.hpp): the registered planar
// motion of keyframe j relative to keyframe i — (x, y) in i's heading frame and the change of yaw —
// against the estimated one, whitened by the registration's information (an upper-triangular
// square root S, SᵀS = information in i's frame). Height, roll and pitch are left to odometry.
struct ScanMatchFactor {
  ScanMatchFactor(const Eigen::Vector3d& measured, const Eigen::Matrix3d& sqrt_information)
      : measured_(measured), sqrt_information_(sqrt_information) {}

  template <typename T>
  static T yawOf(const Eigen::Map<const Eigen::Quaternion<T>>& q) {
    using std::atan2;
    return atan2(T(2.0) * (q.w() * q.z() + q.x() * q.y()),
                 T(1.0) - T(2.0) * (q.y() * q.y() + q.z() * q.z()));
  }

  template <typename T>
  bool operator()(const T* p_i, const T* q_i, const T* p_j, const T* q_j, T* residual) const {
    using std::atan2;
    using std::cos;
    using std::sin;
    const Eigen::Map<const Eigen::Quaternion<T>> qi(q_i), qj(q_j);
    const T yaw_i = yawOf(qi);
    const T dx = p_j[0] - p_i[0], dy = p_j[1] - p_i[1];
    const T c = cos(yaw_i), s = sin(yaw_i);
    Eigen::Matrix<T, 3, 1> e;
    e(0) = c * dx + s * dy - T(measured_.x());
    e(1) = -s * dx + c * dy - T(measured_.y());
    const T dyaw = yawOf(qj) - yaw_i - T(measured_.z());
    e(2) = atan2(sin(dyaw), cos(dyaw));
    const Eigen::Matrix<T, 3, 1> r = sqrt_information_.cast<T>() * e;
    for (int k = 0; k < 3; ++k) residual[k] = r(k);
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Vector3d& measured,
                                     const Eigen::Matrix3d& sqrt_information) {
    return new ceres::AutoDiffCostFunction<ScanMatchFactor, 3, 3, 4, 3, 4>(
        new ScanMatchFactor(measured, sqrt_information));
  }

 private:
  Eigen::Vector3d measured_;
  Eigen::Matrix3d sqrt_information_;
};

// The floors layer (the paper's: a floor node constraining every room of its floor): a room's
// centre ρ stays where it was, relative to its floor's node ξ, when it was first tied to it —
// e = (ρ − ξ − d) / σ. The rooms of one floor keep the layout they were seen in, within σ.
struct FloorRoomFactor {
  FloorRoomFactor(const Eigen::Vector2d& offset, double sigma) : offset_(offset), sigma_(sigma) {}

  template <typename T>
  bool operator()(const T* floor, const T* room, T* residual) const {
    for (int k = 0; k < 2; ++k) residual[k] = (room[k] - floor[k] - T(offset_[k])) / T(sigma_);
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Vector2d& offset, double sigma) {
    return new ceres::AutoDiffCostFunction<FloorRoomFactor, 2, 2, 2>(
        new FloorRoomFactor(offset, sigma));
  }

 private:
  Eigen::Vector2d offset_;
  double sigma_;
};

}  // namespace isg::slam
