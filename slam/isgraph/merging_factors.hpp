#pragma once

#include <ceres/autodiff_cost_function.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "bim/optimizer/plane_manifold.hpp"

namespace isg::slam {

// Graph merging (docs/matching.md): factors between the S-Graph (in M) and the A-Graph (in B)
// through B_T_M. B_T_M is a planar transform [x, y, yaw] (walls do not observe roll, pitch or z;
// the level is flat); its z is held and does not enter these factors.

template <typename T>
Eigen::Matrix<T, 3, 3> yawRotation(const T& yaw) {
  using std::cos;
  using std::sin;
  Eigen::Matrix<T, 3, 3> R = Eigen::Matrix<T, 3, 3>::Identity();
  R(0, 0) = cos(yaw);
  R(0, 1) = -sin(yaw);
  R(1, 0) = sin(yaw);
  R(1, 1) = cos(yaw);
  return R;
}

// Plane-to-plane: (B_T_M · π_M) ⊖ π_B on the plane manifold, whitened.
// Parameters: π_M (4), B_T_M [x, y, yaw] (3), π_B (4).
struct PlanePlaneFactor {
  PlanePlaneFactor(double sigma_angle, double sigma_distance)
      : weights_(1.0 / sigma_angle, 1.0 / sigma_angle, 1.0 / sigma_distance) {}

  template <typename T>
  bool operator()(const T* plane_M, const T* B_T_M, const T* plane_B, T* residual) const {
    const Eigen::Matrix<T, 3, 3> R = yawRotation(B_T_M[2]);
    const Eigen::Matrix<T, 3, 1> t(B_T_M[0], B_T_M[1], T(0));
    const Eigen::Matrix<T, 3, 1> n = R * Eigen::Matrix<T, 3, 1>(plane_M[0], plane_M[1], plane_M[2]);
    Eigen::Matrix<T, 4, 1> in_B;
    in_B << n, plane_M[3] - n.dot(t);
    const Eigen::Matrix<T, 4, 1> b(plane_B[0], plane_B[1], plane_B[2], plane_B[3]);
    const Eigen::Matrix<T, 3, 1> e = bim::planeMinus(in_B, b);
    for (int i = 0; i < 3; ++i) residual[i] = T(weights_(i)) * e(i);
    return true;
  }

  static ceres::CostFunction* create(double sigma_angle, double sigma_distance) {
    return new ceres::AutoDiffCostFunction<PlanePlaneFactor, 3, 4, 3, 4>(
        new PlanePlaneFactor(sigma_angle, sigma_distance));
  }

 private:
  Eigen::Vector3d weights_;
};

// ρ_B − B_T_M · ρ_M: how far the plan's room centre lies from the map's, in B.
template <typename T>
Eigen::Matrix<T, 2, 1> roomDifference(const T* room_M, const T* B_T_M, const T* room_B) {
  using std::cos;
  using std::sin;
  const T c = cos(B_T_M[2]), s = sin(B_T_M[2]);
  return {room_B[0] - (c * room_M[0] - s * room_M[1] + B_T_M[0]),
          room_B[1] - (s * room_M[0] + c * room_M[1] + B_T_M[1])};
}

// Room-to-room: ρ_B − B_T_M · ρ_M, whitened. Parameters: ρ_M (2), B_T_M (3), ρ_B (2).
struct RoomRoomFactor {
  explicit RoomRoomFactor(double sigma) : weight_(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* room_M, const T* B_T_M, const T* room_B, T* residual) const {
    const Eigen::Matrix<T, 2, 1> difference = roomDifference(room_M, B_T_M, room_B);
    residual[0] = T(weight_) * difference.x();
    residual[1] = T(weight_) * difference.y();
    return true;
  }

  static ceres::CostFunction* create(double sigma) {
    return new ceres::AutoDiffCostFunction<RoomRoomFactor, 2, 2, 3, 2>(new RoomRoomFactor(sigma));
  }

 private:
  double weight_;
};

// Room-to-room along one direction only: n · (ρ_B − B_T_M · ρ_M) / σ, n a unit vector in B. A room
// one of whose walls was built off the plan has its S-centre moved along that wall's normal by half
// the wall's offset; its centre still says where the room is along its other pair of walls.
struct RoomRoomAlongFactor {
  RoomRoomAlongFactor(const Eigen::Vector2d& normal, double sigma)
      : normal_(normal.normalized()), weight_(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* room_M, const T* B_T_M, const T* room_B, T* residual) const {
    const Eigen::Matrix<T, 2, 1> difference = roomDifference(room_M, B_T_M, room_B);
    residual[0] = T(weight_) * (T(normal_.x()) * difference.x() + T(normal_.y()) * difference.y());
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Vector2d& normal, double sigma) {
    return new ceres::AutoDiffCostFunction<RoomRoomAlongFactor, 1, 2, 3, 2>(
        new RoomRoomAlongFactor(normal, sigma));
  }

 private:
  Eigen::Vector2d normal_;
  double weight_;
};

// A weak prior on B_T_M [x, y, yaw] at a value: keeps it from running off where the window's
// correspondences constrain it poorly. Residual [(x − x₀)/σ_t, (y − y₀)/σ_t, wrap(yaw − yaw₀)/σ_r].
struct PlanarPriorFactor {
  PlanarPriorFactor(const Eigen::Vector3d& value, double sigma_translation, double sigma_yaw)
      : value_(value), weight_t_(1.0 / sigma_translation), weight_r_(1.0 / sigma_yaw) {}

  template <typename T>
  bool operator()(const T* x, T* residual) const {
    using std::atan2;
    using std::cos;
    using std::sin;
    residual[0] = T(weight_t_) * (x[0] - T(value_.x()));
    residual[1] = T(weight_t_) * (x[1] - T(value_.y()));
    const T dyaw = x[2] - T(value_.z());
    residual[2] = T(weight_r_) * atan2(sin(dyaw), cos(dyaw));
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Vector3d& value, double sigma_translation,
                                     double sigma_yaw) {
    return new ceres::AutoDiffCostFunction<PlanarPriorFactor, 3, 3>(
        new PlanarPriorFactor(value, sigma_translation, sigma_yaw));
  }

 private:
  Eigen::Vector3d value_;
  double weight_t_, weight_r_;
};

// A door jamb seen from a keyframe: the centroid of its points (in R) lies on the jamb's plane
// in P. Residual (n · (P_T_M · M_T_R · c)_xy − n · j) / σ, with n the jamb's normal and j a
// point of it. Parameters: the keyframe's position (3) and orientation (4, Eigen's x y z w),
// P_T_M [x, y, yaw] (3).
struct JambFactor {
  JambFactor(const Eigen::Vector3d& centroid_R, const Eigen::Vector2d& normal,
             const Eigen::Vector2d& point, double sigma)
      : centroid_R_(centroid_R), normal_(normal), d_(normal.dot(point)), weight_(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* position, const T* orientation, const T* P_T_M, T* residual) const {
    const Eigen::Quaternion<T> q(orientation[3], orientation[0], orientation[1], orientation[2]);
    const Eigen::Matrix<T, 3, 1> in_M =
        q.normalized() * centroid_R_.cast<T>() +
        Eigen::Matrix<T, 3, 1>(position[0], position[1], position[2]);
    const Eigen::Matrix<T, 3, 1> in_P = yawRotation(P_T_M[2]) * in_M;
    const T along = T(normal_.x()) * (in_P.x() + P_T_M[0]) + T(normal_.y()) * (in_P.y() + P_T_M[1]);
    residual[0] = T(weight_) * (along - T(d_));
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Vector3d& centroid_R,
                                     const Eigen::Vector2d& normal, const Eigen::Vector2d& point,
                                     double sigma) {
    return new ceres::AutoDiffCostFunction<JambFactor, 1, 3, 4, 3>(
        new JambFactor(centroid_R, normal, point, sigma));
  }

 private:
  Eigen::Vector3d centroid_R_;
  Eigen::Vector2d normal_;
  double d_;
  double weight_;
};

}  // namespace isg::slam
