#include "bim/optimizer/agraph_factors.hpp"

#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include "bim/optimizer/tests/jacobian_check.hpp"

#include <random>

#include "bim/agraph.hpp"
#include "bim/optimizer/plane_manifold.hpp"

namespace isg::bim {
namespace {

Eigen::Vector4d plane(const Eigen::Vector3d& normal, const Eigen::Vector3d& point) {
  return toVector(Plane::throughPoint(normal, point));
}

TEST(PlaneManifold, PlusMinusRoundTrip) {
  PlaneManifold m;
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0.0, 0.3);
  for (int k = 0; k < 50; ++k) {
    Eigen::Vector4d x(noise(rng), noise(rng), noise(rng) + (k % 5 == 0 ? 3.0 : 0.0), noise(rng));
    x.head<3>().normalize();
    const Eigen::Vector3d delta(0.3 * noise(rng), 0.3 * noise(rng), noise(rng));
    Eigen::Vector4d y;
    ASSERT_TRUE(m.Plus(x.data(), delta.data(), y.data()));
    EXPECT_NEAR(y.head<3>().norm(), 1.0, 1e-12);
    Eigen::Vector3d back;
    ASSERT_TRUE(m.Minus(y.data(), x.data(), back.data()));
    EXPECT_NEAR((back - delta).norm(), 0.0, 1e-10);
  }
}

TEST(PlaneManifold, StepOnAWallIsAzimuthAndElevation) {
  PlaneManifold m;
  const Eigen::Vector4d wall(1, 0, 0, -2);  // x = 2
  const Eigen::Vector3d delta(0.1, 0.0, 0.5);
  Eigen::Vector4d moved;
  m.Plus(wall.data(), delta.data(), moved.data());
  // Azimuth turned by 0.1 rad about z, still vertical, 0.5 m further.
  EXPECT_NEAR(moved(0), std::cos(0.1), 1e-12);
  EXPECT_NEAR(moved(1), std::sin(0.1), 1e-12);
  EXPECT_NEAR(moved(2), 0.0, 1e-12);
  EXPECT_NEAR(moved(3), -1.5, 1e-12);
  const Eigen::Vector3d tilt(0.0, 0.2, 0.0);
  m.Plus(wall.data(), tilt.data(), moved.data());
  EXPECT_NEAR(moved(2), std::sin(0.2), 1e-12);  // elevation
}

TEST(PlaneManifold, JacobiansMatchNumericDifferentiation) {
  PlaneManifold m;
  const double h = 1e-7;
  for (const Eigen::Vector4d& x : {Eigen::Vector4d(0.6, 0.8, 0.0, -3.0),
                                   Eigen::Vector4d(0.0, 0.0, 1.0, 1.0),  // horizontal: no pole
                                   Eigen::Vector4d(0.48, -0.6, 0.64, 0.5)}) {
    Eigen::Matrix<double, 4, 3, Eigen::RowMajor> plus;
    m.PlusJacobian(x.data(), plus.data());
    Eigen::Matrix<double, 3, 4, Eigen::RowMajor> minus;
    m.MinusJacobian(x.data(), minus.data());
    for (int i = 0; i < 3; ++i) {
      Eigen::Vector3d d = Eigen::Vector3d::Zero();
      d(i) = h;
      Eigen::Vector4d xp, xm;
      m.Plus(x.data(), d.data(), xp.data());
      d(i) = -h;
      m.Plus(x.data(), d.data(), xm.data());
      EXPECT_NEAR((plus.col(i) - (xp - xm) / (2 * h)).norm(), 0.0, 1e-7);
    }
    for (int j = 0; j < 4; ++j) {
      Eigen::Vector4d yp = x, ym = x;
      yp(j) += h;
      ym(j) -= h;
      Eigen::Vector3d mp, mm;
      m.Minus(yp.data(), x.data(), mp.data());
      m.Minus(ym.data(), x.data(), mm.data());
      EXPECT_NEAR((minus.col(j) - (mp - mm) / (2 * h)).norm(), 0.0, 1e-7) << j;
    }
    // Minus ∘ Plus is the identity on the tangent space.
    EXPECT_NEAR(((minus * plus) - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12);
  }
}

TEST(WallFactor, ZeroAtEquationOneAndJacobiansMatch) {
  // A wall along y at x = 4 (faces x = 3.9 and 4.1), anchor (4, 1, 1.5).
  Eigen::Vector4d a = plane({-1, 0, 0}, {3.9, 0, 0});
  Eigen::Vector4d b = plane({1, 0, 0}, {4.1, 0, 0});
  Eigen::Vector3d centre(4, 1, 1.5);
  std::unique_ptr<ceres::CostFunction> cost(WallFactor::create({4, 1, 1.5}, 0.01));
  double* params[] = {centre.data(), a.data(), b.data()};
  Eigen::Vector3d residual;
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual.norm(), 0.0, 1e-12);
  // Moving the centre by 1 cm costs exactly 1 (whitened by sigma = 1 cm).
  centre.y() += 0.01;
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual.norm(), 1.0, 1e-9);
  PlaneManifold pm;
  a = plane({-0.99, 0.1, 0.02}, {3.9, 0.3, 0});
  isg::testing::expectJacobiansMatchNumeric(*cost, {nullptr, &pm, &pm},
                                            {centre.data(), a.data(), b.data()});
}

TEST(FourWallRoomFactor, ZeroAtTheRoomCentreAndJacobiansMatch) {
  // A room [1, 5] × [2, 4] rotated by 30° about the origin: its centre rotates with it.
  const double t = 0.5235987755982988;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(t, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  Eigen::Vector4d x1 = plane(R * Eigen::Vector3d(1, 0, 0), R * Eigen::Vector3d(1, 0, 0));
  Eigen::Vector4d x2 = plane(R * Eigen::Vector3d(-1, 0, 0), R * Eigen::Vector3d(5, 0, 0));
  Eigen::Vector4d y1 = plane(R * Eigen::Vector3d(0, 1, 0), R * Eigen::Vector3d(0, 2, 0));
  Eigen::Vector4d y2 = plane(R * Eigen::Vector3d(0, -1, 0), R * Eigen::Vector3d(0, 4, 0));
  Eigen::Vector2d room = (R * Eigen::Vector3d(3, 3, 0)).head<2>();
  std::unique_ptr<ceres::CostFunction> cost(FourWallRoomFactor::create(0.01));
  double* params[] = {room.data(), x1.data(), x2.data(), y1.data(), y2.data()};
  Eigen::Vector2d residual;
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual.norm(), 0.0, 1e-12);
  EXPECT_NEAR(
      (fourWallRoomCentre(toPlane(x1), toPlane(x2), toPlane(y1), toPlane(y2)) - room).norm(), 0.0,
      1e-12);
  PlaneManifold pm;
  isg::testing::expectJacobiansMatchNumeric(
      *cost, {nullptr, &pm, &pm, &pm, &pm},
      {room.data(), x1.data(), x2.data(), y1.data(), y2.data()});
}

TEST(TwoWallRoomFactor, ZeroOnTheCorridorAxisEvenThroughTheOrigin) {
  // A corridor y in [-1, 1] along x: its mid-plane passes through the origin (m = 0), where
  // the textbook n̂ = m/|m| is undefined (docs/agraph.md). The factor uses the normal and stays
  // defined.
  Eigen::Vector4d a = plane({0, 1, 0}, {0, -1, 0});
  Eigen::Vector4d b = plane({0, -1, 0}, {0, 1, 0});
  Eigen::Vector2d room(7, 0);
  std::unique_ptr<ceres::CostFunction> cost(TwoWallRoomFactor::create({7, 0.2}, 0.01));
  double* params[] = {room.data(), a.data(), b.data()};
  Eigen::Vector2d residual;
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual.norm(), 0.0, 1e-12);
  PlaneManifold pm;
  isg::testing::expectJacobiansMatchNumeric(*cost, {nullptr, &pm, &pm},
                                            {room.data(), a.data(), b.data()});
}

TEST(DoorwayFactor, ZeroWhenBothRoomsSeeTheDoorWhereItIs) {
  Eigen::Vector2d r1(1, 2), r2(4, 2);
  Eigen::Vector3d door(3, 2.5, 0);
  std::unique_ptr<ceres::CostFunction> cost(
      DoorwayFactor::create(door.head<2>() - r1, door.head<2>() - r2, 0.02));
  double* params[] = {r1.data(), r2.data(), door.data()};
  Eigen::Vector4d residual;
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual.norm(), 0.0, 1e-12);
  // Moving room 2 by 2 cm: its half of the residual is 1, the paper's difference is 1 too.
  r2.x() += 0.02;
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual.head<2>().norm(), 0.0, 1e-12);
  EXPECT_NEAR(residual.tail<2>().norm(), 1.0, 1e-9);
  EXPECT_NEAR((residual.head<2>() - residual.tail<2>()).norm(), 1.0, 1e-9);
  isg::testing::expectJacobiansMatchNumeric(*cost, {nullptr, nullptr, nullptr},
                                            {r1.data(), r2.data(), door.data()});
}

TEST(OutsideDoorwayFactor, ZeroWhenTheRoomSeesTheDoorWhereItIs) {
  Eigen::Vector2d room(2, 1);
  Eigen::Vector3d door(3, 4, 0);
  std::unique_ptr<ceres::CostFunction> cost(
      OutsideDoorwayFactor::create(door.head<2>() - room, 0.02));
  double* params[] = {room.data(), door.data()};
  Eigen::Vector2d residual;
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual.norm(), 0.0, 1e-12);
  // The door 2 cm further along x than the room sees it: (ρ + ᵖD − D)/σ = −0.02/0.02 = −1.
  door.x() += 0.02;
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual(0), -1.0, 1e-9);
  EXPECT_NEAR(residual(1), 0.0, 1e-12);
  isg::testing::expectJacobiansMatchNumeric(*cost, {nullptr, nullptr}, {room.data(), door.data()});
}

TEST(PlanePriorFactor, MinimalResidualAndJacobians) {
  const Eigen::Vector4d measured(0, 1, 0, -3);  // y = 3
  Eigen::Vector4d p = measured;
  std::unique_ptr<ceres::CostFunction> cost(PlanePriorFactor::create(measured, 0.01, 0.02));
  double* params[] = {p.data()};
  Eigen::Vector3d residual;
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual.norm(), 0.0, 1e-12);
  PlaneManifold pm;
  const Eigen::Vector3d step(0.01, 0.0, 0.02);  // 0.01 rad azimuth, 2 cm: one sigma each
  pm.Plus(measured.data(), step.data(), p.data());
  cost->Evaluate(params, residual.data(), nullptr);
  EXPECT_NEAR(residual(0), 1.0, 1e-9);
  EXPECT_NEAR(residual(1), 0.0, 1e-9);
  EXPECT_NEAR(residual(2), 1.0, 1e-9);
  isg::testing::expectJacobiansMatchNumeric(*cost, {&pm}, {p.data()});
}

}  // namespace
}  // namespace isg::bim
