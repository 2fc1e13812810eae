#pragma once

#include <ceres/autodiff_cost_function.h>

#include <Eigen/Core>

#include "bim/optimizer/plane_manifold.hpp"

namespace isg::bim {

// The A-Graph's factors as Ceres cost functions (paper §III, docs/agraph.md). Planes are
// 4-vectors [n, d] on the PlaneManifold, centres plain vectors. The room factors are the same in
// the S-Graph, which uses these classes too. Residuals are whitened by 1/sigma.
//
// Every factor works with closest points cp = -d·n: the maths of "flip the planes to d ≤ 0 and
// take |d|·n" (docs/agraph.md), without the flip (cp does not change when a plane is flipped).

template <typename T>
Eigen::Matrix<T, 3, 1> closestPoint(const T* plane) {
  return Eigen::Matrix<T, 3, 1>(plane[0], plane[1], plane[2]) * (-plane[3]);
}

// Projection of p onto the plane through the origin with normal n (sign of n irrelevant).
template <typename T, typename V>
Eigen::Matrix<T, 3, 1> inPlaneComponent(const V& p, const T* plane) {
  using std::sqrt;
  Eigen::Matrix<T, 3, 1> n(plane[0], plane[1], plane[2]);
  n /= sqrt(n.squaredNorm());
  return p - n * n.dot(p);
}

// Wall: ω − f(π₁, π₂, s), f = ½(cp₁ + cp₂) + [s − (s·n̂)n̂]  (Eq. (1) of the paper).
// Parameters: ω (3), π₁ (4), π₂ (4).
struct WallFactor {
  WallFactor(const Eigen::Vector3d& anchor, double sigma) : anchor_(anchor), weight_(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* centre, const T* a, const T* b, T* residual) const {
    const Eigen::Matrix<T, 3, 1> mid = T(0.5) * (closestPoint(a) + closestPoint(b));
    const Eigen::Matrix<T, 3, 1> f = mid + inPlaneComponent(anchor_.cast<T>().eval(), a);
    for (int i = 0; i < 3; ++i) residual[i] = T(weight_) * (centre[i] - f(i));
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Vector3d& anchor, double sigma) {
    return new ceres::AutoDiffCostFunction<WallFactor, 3, 3, 4, 4>(new WallFactor(anchor, sigma));
  }

 private:
  Eigen::Vector3d anchor_;
  double weight_;
};

// Four-wall room: ρ − [½(cp_x1 + cp_x2) + ½(cp_y1 + cp_y2)].xy.
// Parameters: ρ (2), π_x1, π_x2, π_y1, π_y2 (4 each).
struct FourWallRoomFactor {
  explicit FourWallRoomFactor(double sigma) : weight_(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* room, const T* x1, const T* x2, const T* y1, const T* y2,
                  T* residual) const {
    const Eigen::Matrix<T, 3, 1> centre = T(0.5) * (closestPoint(x1) + closestPoint(x2)) +
                                          T(0.5) * (closestPoint(y1) + closestPoint(y2));
    residual[0] = T(weight_) * (room[0] - centre.x());
    residual[1] = T(weight_) * (room[1] - centre.y());
    return true;
  }

  static ceres::CostFunction* create(double sigma) {
    return new ceres::AutoDiffCostFunction<FourWallRoomFactor, 2, 2, 4, 4, 4, 4>(
        new FourWallRoomFactor(sigma));
  }

 private:
  double weight_;
};

// Two-wall room (corridor): ρ − [m + (c − (c·n̂)n̂)].xy with m = ½(cp₁ + cp₂) and c a point on the
// corridor's axis. The textbook form n̂ = m/|m| (docs/agraph.md), which is n̂ = ±n except where the
// corridor's mid-plane passes through the origin of B and m = 0; we use the planes' normal, which
// is the same wherever both are defined and never singular. Parameters: ρ (2), π₁, π₂ (4 each).
struct TwoWallRoomFactor {
  TwoWallRoomFactor(const Eigen::Vector2d& axis_point, double sigma)
      : axis_point_(axis_point.x(), axis_point.y(), 0.0), weight_(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* room, const T* a, const T* b, T* residual) const {
    const Eigen::Matrix<T, 3, 1> mid = T(0.5) * (closestPoint(a) + closestPoint(b));
    const Eigen::Matrix<T, 3, 1> f = mid + inPlaneComponent(axis_point_.cast<T>().eval(), a);
    residual[0] = T(weight_) * (room[0] - f.x());
    residual[1] = T(weight_) * (room[1] - f.y());
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Vector2d& axis_point, double sigma) {
    return new ceres::AutoDiffCostFunction<TwoWallRoomFactor, 2, 2, 4, 4>(
        new TwoWallRoomFactor(axis_point, sigma));
  }

 private:
  Eigen::Vector3d axis_point_;
  double weight_;
};

// Doorway: the door seen from each room it joins, (ρᵢ + ᵖⁱD) − D.xy for i = 1, 2, where ᵖⁱD is the
// door's position relative to room i in the plan. The paper's ‖(ρ₁ + ρ₁D) − (ρ₂ + ρ₂D)‖ is the
// difference of the two halves; keeping D in the factor also estimates the doorway node.
// Parameters: ρ₁ (2), ρ₂ (2), D (3).
struct DoorwayFactor {
  DoorwayFactor(const Eigen::Vector2d& from_room1, const Eigen::Vector2d& from_room2, double sigma)
      : from_room1_(from_room1), from_room2_(from_room2), weight_(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* room1, const T* room2, const T* door, T* residual) const {
    for (int i = 0; i < 2; ++i) {
      residual[i] = T(weight_) * (room1[i] + T(from_room1_(i)) - door[i]);
      residual[2 + i] = T(weight_) * (room2[i] + T(from_room2_(i)) - door[i]);
    }
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Vector2d& from_room1,
                                     const Eigen::Vector2d& from_room2, double sigma) {
    return new ceres::AutoDiffCostFunction<DoorwayFactor, 4, 2, 2, 3>(
        new DoorwayFactor(from_room1, from_room2, sigma));
  }

 private:
  Eigen::Vector2d from_room1_;
  Eigen::Vector2d from_room2_;
  double weight_;
};

// A door to the outside is seen from one room only: (ρ + ᵖD) − D.xy. Parameters: ρ (2), D (3).
struct OutsideDoorwayFactor {
  OutsideDoorwayFactor(const Eigen::Vector2d& from_room, double sigma)
      : from_room_(from_room), weight_(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* room, const T* door, T* residual) const {
    for (int i = 0; i < 2; ++i) residual[i] = T(weight_) * (room[i] + T(from_room_(i)) - door[i]);
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Vector2d& from_room, double sigma) {
    return new ceres::AutoDiffCostFunction<OutsideDoorwayFactor, 2, 2, 3>(
        new OutsideDoorwayFactor(from_room, sigma));
  }

 private:
  Eigen::Vector2d from_room_;
  double weight_;
};

// A plane measured directly (the plan's surface, or a matched surface): π ⊖ π₀ in the minimal
// (azimuth, elevation, distance) form, whitened per component. Parameters: π (4).
struct PlanePriorFactor {
  PlanePriorFactor(const Eigen::Vector4d& measured, double sigma_angle, double sigma_distance)
      : measured_(measured), weights_(1.0 / sigma_angle, 1.0 / sigma_angle, 1.0 / sigma_distance) {}

  template <typename T>
  bool operator()(const T* plane, T* residual) const {
    const Eigen::Matrix<T, 4, 1> p(plane[0], plane[1], plane[2], plane[3]);
    const Eigen::Matrix<T, 3, 1> e = planeMinus(p, measured_);
    for (int i = 0; i < 3; ++i) residual[i] = T(weights_(i)) * e(i);
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Vector4d& measured, double sigma_angle,
                                     double sigma_distance) {
    return new ceres::AutoDiffCostFunction<PlanePriorFactor, 3, 4>(
        new PlanePriorFactor(measured, sigma_angle, sigma_distance));
  }

 private:
  Eigen::Vector4d measured_;
  Eigen::Vector3d weights_;
};

}  // namespace isg::bim
