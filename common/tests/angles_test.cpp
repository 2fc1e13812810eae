#include "common/angles.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

namespace isg::common {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(Angles, WrapKeepsTheHalfTurnsSign) {
  EXPECT_DOUBLE_EQ(wrapAngle(0.25), 0.25);
  EXPECT_DOUBLE_EQ(wrapAngle(2 * kPi + 0.25), 0.25);
  EXPECT_NEAR(wrapAngle(-2 * kPi - 0.25), -0.25, 1e-15);
  EXPECT_NEAR(wrapAngle(1.5 * kPi), -0.5 * kPi, 1e-15);
  EXPECT_NEAR(wrapAngle(-1.5 * kPi), 0.5 * kPi, 1e-15);
  EXPECT_DOUBLE_EQ(wrapAngle(kPi), kPi);
  EXPECT_DOUBLE_EQ(wrapAngle(-kPi), -kPi);
  // Many turns away: the same angle, to the rounding of the many turns.
  EXPECT_NEAR(wrapAngle(0.3 + 200 * kPi), 0.3, 1e-12);
}

TEST(Angles, DifferenceIsInTheHalfOpenTurn) {
  EXPECT_DOUBLE_EQ(angleDifference(0.5, 0.25), 0.25);
  // 179° − (−179°) is −2°, not 358°.
  const double deg = kPi / 180;
  EXPECT_NEAR(angleDifference(179 * deg, -179 * deg), -2 * deg, 1e-12);
  EXPECT_NEAR(angleDifference(-179 * deg, 179 * deg), 2 * deg, 1e-12);
  // A half turn either way is +π.
  EXPECT_DOUBLE_EQ(angleDifference(kPi, 0.0), kPi);
  EXPECT_DOUBLE_EQ(angleDifference(-kPi, 0.0), kPi);
  EXPECT_DOUBLE_EQ(angleDifference(0.0, kPi), kPi);
}

TEST(Angles, RemainderIsStdRemainderBitForBit) {
  // Random angles over many turns, every multiple of the period's fractions (exact ties and their
  // neighbours one ulp away), zeros of both signs, and what falls back to std::remainder.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(-40.0, 40.0);
  std::vector<double> xs = {0.0, -0.0, 1e12, -1e300, std::numeric_limits<double>::infinity()};
  for (int i = 0; i < 200000; ++i) xs.push_back(angle(rng));
  for (int k = -12; k <= 12; ++k) {
    for (double period : {2 * kPi, kPi, kPi / 2}) {
      const double x = 0.5 * k * period;
      xs.insert(xs.end(), {x, std::nextafter(x, 1e9), std::nextafter(x, -1e9)});
    }
  }
  for (double period : {2 * kPi, kPi, kPi / 2}) {
    for (double x : xs) {
      const double expected = std::remainder(x, period), got = remainderOf(x, period);
      ASSERT_EQ(std::memcmp(&expected, &got, sizeof(double)), 0)
          << "x " << x << " period " << period << ": " << got << " for " << expected;
    }
  }
  EXPECT_TRUE(std::isnan(remainderOf(std::nan(""), kPi)));
}

TEST(Angles, HeadingAndYaw) {
  EXPECT_DOUBLE_EQ(headingOf({1.0, 0.0}), 0.0);
  EXPECT_DOUBLE_EQ(headingOf({0.0, 2.0}), kPi / 2);
  EXPECT_DOUBLE_EQ(headingOf({-1.0, 1.0}), 0.75 * kPi);
  EXPECT_DOUBLE_EQ(headingOf({-1.0, 0.0}), kPi);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(-2.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_NEAR(yawOf(R), -2.0, 1e-15);
  // A small roll and pitch leave the yaw of the x axis's heading.
  const Eigen::Matrix3d tilted = R * Eigen::AngleAxisd(0.02, Eigen::Vector3d::UnitX()) *
                                 Eigen::AngleAxisd(0.03, Eigen::Vector3d::UnitY());
  EXPECT_NEAR(yawOf(tilted), headingOf(tilted.col(0).head<2>()), 1e-15);
}

}  // namespace
}  // namespace isg::common
