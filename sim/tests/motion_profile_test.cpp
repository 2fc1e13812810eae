#include "sim/motion_profile.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace isg::sim {
namespace {

using std::numbers::pi;

TEST(RestToRestProfile, RampsHoldsAndStopsAtTheDistance) {
  // 2 m at 0.5 m/s, 1.5 m/s² at most: ramps of π·0.5 / (2·1.5) = 0.5236 s cover 0.1309 m each.
  const RestToRestProfile p(2.0, 0.5, 1.5);
  const double ramp = pi / 6.0;
  EXPECT_NEAR(p.duration(), 4.0 + ramp, 1e-12);
  EXPECT_NEAR(p.peakRate(), 0.5, 1e-12);
  EXPECT_NEAR(p.at(ramp).distance, 0.25 * ramp, 1e-12);
  EXPECT_NEAR(p.at(ramp).rate, 0.5, 1e-12);
  EXPECT_NEAR(p.at(ramp / 2).acceleration, 1.5, 1e-12);  // the largest, mid-ramp
  EXPECT_NEAR(p.at(ramp / 2).rate, 0.25, 1e-12);
  EXPECT_NEAR(p.at(2.0).acceleration, 0.0, 1e-12);
  EXPECT_NEAR(p.at(p.duration() - ramp / 2).acceleration, -1.5, 1e-12);
  EXPECT_NEAR(p.at(p.duration()).distance, 2.0, 1e-12);
  EXPECT_NEAR(p.at(p.duration()).rate, 0.0, 1e-12);
  EXPECT_NEAR(p.at(p.duration() + 5.0).distance, 2.0, 1e-12);  // clamped
  EXPECT_NEAR(p.at(-1.0).distance, 0.0, 1e-12);
}

TEST(RestToRestProfile, AShortMoveKeepsTheRampAndPeaksLower) {
  const RestToRestProfile p(0.1, 0.5, 1.5);  // less than the 0.2618 m two full ramps need
  const double ramp = pi / 6.0;
  EXPECT_NEAR(p.duration(), 2.0 * ramp, 1e-12);
  EXPECT_NEAR(p.peakRate(), 0.1 / ramp, 1e-12);
  EXPECT_NEAR(p.at(ramp).distance, 0.05, 1e-12);
  EXPECT_NEAR(p.at(p.duration()).distance, 0.1, 1e-12);
  EXPECT_EQ(RestToRestProfile(0.0, 0.5, 1.5).duration(), 0.0);
}

TEST(RestToRestProfile, RateAndAccelerationAreTheDerivatives) {
  const RestToRestProfile p(1.3, 0.8, 3.0);
  const double h = 1e-5;
  for (double tau = h; tau < p.duration() - h; tau += 0.01) {
    const double rate = (p.at(tau + h).distance - p.at(tau - h).distance) / (2 * h);
    const double acceleration = (p.at(tau + h).rate - p.at(tau - h).rate) / (2 * h);
    EXPECT_NEAR(p.at(tau).rate, rate, 1e-8) << tau;
    EXPECT_NEAR(p.at(tau).acceleration, acceleration, 1e-6) << tau;
  }
}

}  // namespace
}  // namespace isg::sim
