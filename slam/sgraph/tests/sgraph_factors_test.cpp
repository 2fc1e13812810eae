#include "slam/sgraph/sgraph_factors.hpp"

#include <ceres/autodiff_cost_function.h>
#include <ceres/gradient_checker.h>
#include <ceres/manifold.h>
#include <gtest/gtest.h>
#include <numbers>

#include "bim/optimizer/tests/jacobian_check.hpp"
#include "slam/sgraph/tests/test_poses.hpp"

#include <cmath>
#include <memory>
#include <vector>

namespace isg::slam {
namespace {

using isg::testing::pose;

TEST(PosePlaneFactor, ResidualByHandAndJacobians) {
  // The wall x = 5 in M (normal -x, facing the robot), the robot at (1, 2) turned by 90°, the
  // LiDAR 0.25 m above the base. Turned by 90°, L's y axis points along M's -x, so in L the wall
  // is 4 m away with normal n_L = Rᵀ(-1, 0, 0) = (0, 1, 0).
  const Eigen::Isometry3d M_T_R = pose(1, 2, 0.46, std::numbers::pi / 2);
  Eigen::Isometry3d R_T_L = Eigen::Isometry3d::Identity();
  R_T_L.translation() = Eigen::Vector3d(0, 0, 0.25);
  Eigen::Vector4d wall(-1, 0, 0, 5);
  const Eigen::Vector4d measured(0, 1, 0, 4);
  Eigen::Vector3d position = M_T_R.translation();
  Eigen::Quaterniond q(M_T_R.rotation());
  std::unique_ptr<ceres::CostFunction> cost(PosePlaneFactor::create(measured, R_T_L, 0.01, 0.02));
  double* params[] = {position.data(), q.coeffs().data(), wall.data()};
  Eigen::Vector3d residual;
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual.norm(), 0.0, 1e-9);
  // The robot 2 cm nearer the wall: the distance residual is -0.02 / 0.02 = -1.
  position.x() += 0.02;
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual(0), 0.0, 1e-9);
  EXPECT_NEAR(residual(1), 0.0, 1e-9);
  EXPECT_NEAR(residual(2), -1.0, 1e-9);
  // Jacobians (through both manifolds) against numeric differentiation, at a tilted pose.
  q = Eigen::Quaterniond(pose(0, 0, 0, 0.3, 0.1).rotation());
  ceres::EigenQuaternionManifold quaternion;
  bim::PlaneManifold plane;
  isg::testing::expectJacobiansMatchNumeric(*cost, {nullptr, &quaternion, &plane},
                                            {position.data(), q.coeffs().data(), wall.data()});
}

// The residual as the S-Graph wrote it before its Jacobians were written by hand, differentiated
// by Ceres' AutoDiff: the hand-written factor must give the same residual (to rounding) and the
// same Jacobians through both manifolds, far from the measurement too (where numeric
// differentiation through the quaternion's ambient space is no longer a reference).
struct PosePlaneByAutoDiff {
  Eigen::Vector4d measured;
  Eigen::Isometry3d R_T_L;
  Eigen::Vector3d weights;
  template <typename T>
  bool operator()(const T* position, const T* orientation, const T* plane, T* residual) const {
    const Eigen::Map<const Eigen::Quaternion<T>> q(orientation);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> p(position);
    const Eigen::Matrix<T, 3, 3> R = q.toRotationMatrix() * R_T_L.rotation().cast<T>();
    const Eigen::Matrix<T, 3, 1> t = q * R_T_L.translation().cast<T>() + p;
    const Eigen::Matrix<T, 3, 1> n(plane[0], plane[1], plane[2]);
    Eigen::Matrix<T, 4, 1> predicted;
    predicted.template head<3>() = R.transpose() * n;
    predicted(3) = plane[3] + n.dot(t);
    const Eigen::Matrix<T, 3, 1> e = bim::planeMinus(predicted, measured);
    for (int i = 0; i < 3; ++i) residual[i] = T(weights(i)) * e(i);
    return true;
  }
};

TEST(PosePlaneFactor, HandWrittenJacobiansAreAutoDiffs) {
  ceres::EigenQuaternionManifold quaternion;
  Eigen::Isometry3d R_T_L = pose(0.1, -0.05, 0.3, 0.2, 0.01);
  // Poses turned and tilted, planes walls and a floor, measured off the prediction.
  const Eigen::Isometry3d poses[] = {pose(1, 2, 0.4, 0.3, 0.1), pose(-3, 5, 0.5, 2.5, -0.05),
                                     pose(10, -4, 0.45, -1.2, 0.02)};
  const Eigen::Vector4d planes[] = {Eigen::Vector4d(-1, 0, 0, 5),
                                    Eigen::Vector4d(0.6, 0.8, 0.0, -2),
                                    Eigen::Vector4d(0.01, 0.02, 1.0, 0.1)};
  const Eigen::Vector4d measured[] = {Eigen::Vector4d(0.1, 0.99, 0.05, 4),
                                      Eigen::Vector4d(-0.7, 0.7, 0.1, 1.5),
                                      Eigen::Vector4d(0.0, 0.05, -1.0, 0.6)};
  for (const Eigen::Isometry3d& M_T_R : poses) {
    for (const Eigen::Vector4d& wall : planes) {
      for (const Eigen::Vector4d& z : measured) {
        std::unique_ptr<ceres::CostFunction> hand(PosePlaneFactor::create(z, R_T_L, 0.01, 0.02));
        ceres::AutoDiffCostFunction<PosePlaneByAutoDiff, 3, 3, 4, 4> automatic(
            new PosePlaneByAutoDiff{z, R_T_L, Eigen::Vector3d(100.0, 100.0, 50.0)});
        Eigen::Vector3d position = M_T_R.translation();
        Eigen::Quaterniond q(M_T_R.rotation());
        Eigen::Vector4d pi = wall;
        double* params[] = {position.data(), q.coeffs().data(), pi.data()};
        Eigen::Vector3d r_hand, r_auto;
        Eigen::Matrix<double, 3, 3, Eigen::RowMajor> Jp_hand, Jp_auto;
        Eigen::Matrix<double, 3, 4, Eigen::RowMajor> Jq_hand, Jq_auto, Jn_hand, Jn_auto;
        double* j_hand[] = {Jp_hand.data(), Jq_hand.data(), Jn_hand.data()};
        double* j_auto[] = {Jp_auto.data(), Jq_auto.data(), Jn_auto.data()};
        ASSERT_TRUE(hand->Evaluate(params, r_hand.data(), j_hand));
        ASSERT_TRUE(automatic.Evaluate(params, r_auto.data(), j_auto));
        // Eigen's vectorised double paths and its scalar paths for dual numbers round apart.
        for (int i = 0; i < 3; ++i)
          EXPECT_NEAR(r_hand(i), r_auto(i), 1e-12 * std::abs(r_auto(i)) + 1e-12);
        EXPECT_LT((Jp_hand - Jp_auto).cwiseAbs().maxCoeff(), 1e-9);
        EXPECT_LT((Jn_hand - Jn_auto).cwiseAbs().maxCoeff(), 1e-9);
        // The quaternion's through the manifold: only its tangent space is used.
        Eigen::Matrix<double, 4, 3, Eigen::RowMajor> plus;
        quaternion.PlusJacobian(q.coeffs().data(), plus.data());
        EXPECT_LT((Jq_hand * plus - Jq_auto * plus).cwiseAbs().maxCoeff(), 1e-9);
      }
    }
  }
}

TEST(OdometryFactor, ZeroAtTheMeasurementAndJacobians) {
  const Eigen::Isometry3d a = pose(1, 2, 0, 0.3), b = pose(2.5, 2.2, 0.05, 0.8, 0.02);
  const Eigen::Isometry3d delta = a.inverse() * b;
  std::unique_ptr<ceres::CostFunction> cost(OdometryFactor::create(delta, 0.05, 0.01));
  Eigen::Vector3d pa = a.translation(), pb = b.translation();
  Eigen::Quaterniond qa(a.rotation()), qb(b.rotation());
  double* params[] = {pa.data(), qa.coeffs().data(), pb.data(), qb.coeffs().data()};
  Eigen::Matrix<double, 6, 1> residual;
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual.norm(), 0.0, 1e-9);
  // Keyframe j turned by a further 0.01 rad about z: the rotation residual is 1 (2·sin(0.005) /
  // 0.01 ≈ 1) and the translation one 0.
  qb = qb * Eigen::Quaterniond(Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitZ()));
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual.head<3>().norm(), 0.0, 1e-9);
  EXPECT_NEAR(residual.tail<3>().norm(), 2 * std::sin(0.005) / 0.01, 1e-9);
  ceres::EigenQuaternionManifold quaternion;
  isg::testing::expectJacobiansMatchNumeric(
      *cost, {nullptr, &quaternion, nullptr, &quaternion},
      {pa.data(), qa.coeffs().data(), pb.data(), qb.coeffs().data()});
}

TEST(GravityFactor, ResidualByHandIgnoresYaw) {
  // The IMU says R stands level: up in R is z. A keyframe turned by any yaw is level too.
  std::unique_ptr<ceres::CostFunction> cost(GravityFactor::create(Eigen::Vector3d::UnitZ(), 0.01));
  Eigen::Quaterniond q(Eigen::AngleAxisd(2.3, Eigen::Vector3d::UnitZ()));
  double* params[] = {q.coeffs().data()};
  Eigen::Vector3d residual;
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual.norm(), 0.0, 1e-12);
  // Rolled by 10°: up in R is off by a chord of 2·sin(5°), over σ.
  q = q * Eigen::Quaterniond(
              Eigen::AngleAxisd(10.0 * std::numbers::pi / 180, Eigen::Vector3d::UnitX()));
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual.norm(), 2.0 * std::sin(5.0 * std::numbers::pi / 180) / 0.01, 1e-9);
}

TEST(HeightFactor, ResidualByHand) {
  std::unique_ptr<ceres::CostFunction> cost(HeightFactor::create(0.46, 0.05));
  Eigen::Vector3d position(3.0, -2.0, 0.56);
  double* params[] = {position.data()};
  double residual = 0.0;
  cost->Evaluate(params, &residual, nullptr);
  EXPECT_NEAR(residual, 0.1 / 0.05, 1e-12);
}

TEST(FloorRoomFactor, ResidualByHandAndJacobians) {
  // A room tied 2 m east and 2 m north of its floor's node (d), now at (3, 4) with the node at
  // (1, 1): 0 m east, 1 m north off, over σ 0.5 m.
  std::unique_ptr<ceres::CostFunction> cost(FloorRoomFactor::create({2.0, 2.0}, 0.5));
  Eigen::Vector2d floor(1.0, 1.0), room(3.0, 4.0);
  double* params[] = {floor.data(), room.data()};
  Eigen::Vector2d residual;
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual.x(), 0.0, 1e-12);
  EXPECT_NEAR(residual.y(), 2.0, 1e-12);
  // Both moved together: no residual (only the layout is constrained).
  floor += Eigen::Vector2d(5.0, -7.0);
  room += Eigen::Vector2d(5.0, -7.0);
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual.y(), 2.0, 1e-12);
  isg::testing::expectJacobiansMatchNumeric(*cost, {nullptr, nullptr}, {floor.data(), room.data()});
}

}  // namespace
}  // namespace isg::slam
