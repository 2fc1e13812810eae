// Graph merging's factors (slam/isgraph/merging_factors.hpp) like their siblings: zero at the
// truth, a residual worked out by hand one sigma away, and Jacobians that match numeric
// differentiation.
#include "slam/isgraph/merging_factors.hpp"

#include <ceres/manifold.h>
#include <gtest/gtest.h>

#include <memory>
#include <numbers>

#include "bim/optimizer/plane_manifold.hpp"
#include "bim/optimizer/tests/jacobian_check.hpp"
#include "bim/plane.hpp"
#include "slam/sgraph/sgraph_factors.hpp"
#include "slam/sgraph/tests/test_poses.hpp"

namespace isg::slam {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(PlanePlaneFactor, ZeroWhenB_T_MCarriesTheMapWallOntoThePlanWall) {
  // The wall x = 3 of M, and B_T_M = (1, 2, 0.5 rad): in B the wall goes through
  // R·(3, 0, 0) + t with the normal R·(1, 0, 0).
  Eigen::Vector3d B_T_M(1.0, 2.0, 0.5);
  const Eigen::Matrix3d R = yawRotation(B_T_M.z());
  const Eigen::Vector3d t(B_T_M.x(), B_T_M.y(), 0.0);
  Eigen::Vector4d wall_M = bim::toVector(bim::Plane::throughPoint({1, 0, 0}, {3, 0, 0}));
  Eigen::Vector4d wall_B = bim::toVector(
      bim::Plane::throughPoint(R * Eigen::Vector3d(1, 0, 0), R * Eigen::Vector3d(3, 0, 0) + t));
  std::unique_ptr<ceres::CostFunction> cost(PlanePlaneFactor::create(0.01, 0.02));
  double* params[] = {wall_M.data(), B_T_M.data(), wall_B.data()};
  Eigen::Vector3d residual;
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual.norm(), 0.0, 1e-12);
  // B_T_M moved 2 cm along the wall's normal in B: the angles still agree, the distance is one
  // sigma off.
  B_T_M.head<2>() += 0.02 * (R * Eigen::Vector3d(1, 0, 0)).head<2>();
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual(0), 0.0, 1e-9);
  EXPECT_NEAR(residual(1), 0.0, 1e-9);
  EXPECT_NEAR(std::abs(residual(2)), 1.0, 1e-9);
  bim::PlaneManifold plane;
  isg::testing::expectJacobiansMatchNumeric(*cost, {&plane, nullptr, &plane},
                                            {wall_M.data(), B_T_M.data(), wall_B.data()});
}

TEST(RoomRoomFactor, ZeroWhenB_T_MCarriesTheMapRoomOntoThePlanRoom) {
  // ρ_M = (1, 1) turned by 90° is (−1, 1), moved by (2, −1) is (1, 0).
  Eigen::Vector2d room_M(1, 1), room_B(1, 0);
  Eigen::Vector3d B_T_M(2.0, -1.0, kPi / 2);
  std::unique_ptr<ceres::CostFunction> cost(RoomRoomFactor::create(0.05));
  double* params[] = {room_M.data(), B_T_M.data(), room_B.data()};
  Eigen::Vector2d residual;
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual.norm(), 0.0, 1e-12);
  // The plan's room 5 cm further along y: (ρ_B − B_T_M·ρ_M)/σ = (0, 1).
  room_B.y() += 0.05;
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual(0), 0.0, 1e-12);
  EXPECT_NEAR(residual(1), 1.0, 1e-9);
  isg::testing::expectJacobiansMatchNumeric(*cost, {nullptr, nullptr, nullptr},
                                            {room_M.data(), B_T_M.data(), room_B.data()});
}

TEST(RoomRoomAlongFactor, SeesOnlyTheOffsetAlongItsNormal) {
  // The same rooms as above: B_T_M carries ρ_M onto (1, 0).
  Eigen::Vector2d room_M(1, 1), room_B(1, 0);
  Eigen::Vector3d B_T_M(2.0, -1.0, kPi / 2);
  // Along (3, 4)/5, σ 0.05 m.
  std::unique_ptr<ceres::CostFunction> cost(
      RoomRoomAlongFactor::create(Eigen::Vector2d(3.0, 4.0), 0.05));
  double* params[] = {room_M.data(), B_T_M.data(), room_B.data()};
  double residual = 1.0;
  cost->Evaluate(params, &residual, nullptr);
  EXPECT_NEAR(residual, 0.0, 1e-12);
  // 0.25 m across the normal: nothing.
  room_B += 0.25 * Eigen::Vector2d(0.8, -0.6);
  cost->Evaluate(params, &residual, nullptr);
  EXPECT_NEAR(residual, 0.0, 1e-12);
  // 0.1 m more along it: two sigmas.
  room_B += 0.1 * Eigen::Vector2d(0.6, 0.8);
  cost->Evaluate(params, &residual, nullptr);
  EXPECT_NEAR(residual, 2.0, 1e-9);
  isg::testing::expectJacobiansMatchNumeric(*cost, {nullptr, nullptr, nullptr},
                                            {room_M.data(), B_T_M.data(), room_B.data()});
}

TEST(PlanarPriorFactor, ZeroAtItsValueAndTheYawWrapped) {
  const Eigen::Vector3d value(1.0, 2.0, kPi - 0.01);
  std::unique_ptr<ceres::CostFunction> cost(PlanarPriorFactor::create(value, 0.5, 0.02));
  Eigen::Vector3d x = value;
  double* params[] = {x.data()};
  Eigen::Vector3d residual;
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual.norm(), 0.0, 1e-12);
  // Across the half turn: −π + 0.01 is 0.02 rad past π − 0.01, one sigma, not 2π − 0.02.
  x = Eigen::Vector3d(1.5, 2.0, -kPi + 0.01);
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual(0), 1.0, 1e-12);
  EXPECT_NEAR(residual(1), 0.0, 1e-12);
  EXPECT_NEAR(residual(2), 1.0, 1e-9);
  isg::testing::expectJacobiansMatchNumeric(*cost, {nullptr}, {x.data()});
}

using isg::testing::pose;

TEST(ScanMatchFactor, ZeroAtThePlanarMeasurementAndJacobians) {
  // Keyframe j seen from keyframe i in the plane: (Δx, Δy) turned into i's heading, and the turn.
  const Eigen::Isometry3d a = pose(1, 2, 0, 0.3, 0.02), b = pose(2.5, 2.2, 0.05, 0.8, -0.01);
  const double c = std::cos(0.3), s = std::sin(0.3);
  const Eigen::Vector3d measured(c * 1.5 + s * 0.2, -s * 1.5 + c * 0.2, 0.5);
  const Eigen::Matrix3d sqrt_information = Eigen::Vector3d(20, 20, 100).asDiagonal();
  std::unique_ptr<ceres::CostFunction> cost(ScanMatchFactor::create(measured, sqrt_information));
  Eigen::Vector3d pa = a.translation(), pb = b.translation();
  Eigen::Quaterniond qa(a.rotation()), qb(b.rotation());
  double* params[] = {pa.data(), qa.coeffs().data(), pb.data(), qb.coeffs().data()};
  Eigen::Vector3d residual;
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual.norm(), 0.0, 1e-9);
  // Keyframe j turned 0.01 rad further about z (one sigma) and lifted 1 m (z is not observed).
  qb = Eigen::Quaterniond(pose(0, 0, 0, 0.81, -0.01).rotation());
  pb.z() += 1.0;
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual.head<2>().norm(), 0.0, 1e-9);
  EXPECT_NEAR(residual(2), 1.0, 1e-9);
  ceres::EigenQuaternionManifold quaternion;
  isg::testing::expectJacobiansMatchNumeric(
      *cost, {nullptr, &quaternion, nullptr, &quaternion},
      {pa.data(), qa.coeffs().data(), pb.data(), qb.coeffs().data()});
}

}  // namespace
}  // namespace isg::slam
