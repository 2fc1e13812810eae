#include "bim/plane.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace isg::bim {
namespace {

TEST(Plane, ThroughPointHasTheConvention) {
  // The plane x = 2 with its normal along +x: n = (1, 0, 0), d = -2, closest point (2, 0, 0).
  const Plane p = Plane::throughPoint({3, 0, 0}, {2, 5, 7});
  EXPECT_NEAR(p.normal.x(), 1.0, 1e-15);
  EXPECT_NEAR(p.d, -2.0, 1e-15);
  EXPECT_NEAR((p.closestPoint() - Eigen::Vector3d(2, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(p.signedDistance({5, 1, 1}), 3.0, 1e-15);
}

TEST(Plane, TransformFollowsNPrimeEqualsRnAndDPrimeEqualsDMinusNPrimeDotT) {
  const Plane p = Plane::throughPoint({1, 0, 0}, {2, 0, 0});
  // Turn 90° about z and move by (1, 3, 0): x = 2 in the source frame becomes y = 2 + 3 = 5.
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(1, 3, 0);
  const Plane q = p.transformed(T);
  EXPECT_NEAR((q.normal - Eigen::Vector3d(0, 1, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(q.d, -5.0, 1e-12);
  // Every point of the plane maps onto the transformed plane.
  for (const Eigen::Vector3d& point : {Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(2, -4, 9)}) {
    EXPECT_NEAR(q.signedDistance(T * point), 0.0, 1e-12);
  }
}

TEST(Plane, FlippedIsTheSamePlane) {
  const Plane p = Plane::throughPoint({0, 1, 0}, {0, 3, 0});
  const Plane f = p.flipped();
  EXPECT_NEAR(f.signedDistance({7, 3, 1}), 0.0, 1e-15);
  EXPECT_NEAR(f.signedDistance({0, 4, 0}), -1.0, 1e-15);
}

}  // namespace
}  // namespace isg::bim
