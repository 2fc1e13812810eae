// The report's thresholds as the map's noise around a wall sets them, by hand: DeviationOptions'
// defaults (shift 6 cm, angle 1.5°, noise factor 3, five walls at least, angles of walls 1 m long).
#include "slam/deviations/deviation_threshold.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace isg::slam {
namespace {

TEST(DeviationThreshold, FiveWallsAroundSetTheirNoiseScaledForThePlacementsThreeNumbers) {
  const DeviationOptions options;
  DeviationThreshold threshold(options);
  // Five walls 2 m long, each 1 cm off and 0.2° turned: mean square 1e-4 m², 0.04 deg², scaled
  // by 5 / (5 − 3).
  for (int i = 0; i < 5; ++i) EXPECT_TRUE(threshold.addNeighbour(2.0, 2.0, 0.01, 0.2));
  ASSERT_TRUE(threshold.offsetNoise() && threshold.angleNoise());
  EXPECT_NEAR(*threshold.offsetNoise(), std::sqrt(1e-4 * 2.5), 1e-15);
  EXPECT_NEAR(*threshold.angleNoise(), std::sqrt(0.04 * 2.5), 1e-14);
  // 3 × 1.58 cm = 4.7 cm is below the 6 cm floor; 3 × 0.316° = 0.95° below 1.5°.
  WallThresholds t = threshold.thresholds(0.0);
  EXPECT_EQ(t.shift_m, 0.06);
  EXPECT_EQ(t.angle_deg, 1.5);
  // A placement that fixes the map across the wall only to 3 cm: the shift threshold is 9 cm.
  EXPECT_NEAR(threshold.thresholds(0.03).shift_m, 0.09, 1e-15);
  // A noisier map: walls 4 cm off and 0.8° turned raise both above the floor.
  DeviationThreshold noisy(options);
  for (int i = 0; i < 6; ++i) noisy.addNeighbour(1.5, 1.5, i % 2 ? 0.04 : -0.04, 0.8);
  t = noisy.thresholds(0.0);
  EXPECT_NEAR(t.shift_m, 3.0 * 0.04 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(t.angle_deg, 3.0 * 0.8 * std::sqrt(2.0), 1e-12);
}

TEST(DeviationThreshold, AWallThatDeviatesItselfOrIsShortDoesNotCountForTheNoise) {
  const DeviationOptions options;
  DeviationThreshold threshold(options);
  EXPECT_FALSE(threshold.addNeighbour(2.0, 2.0, 0.07, 0.0));  // shifted by 7 cm
  EXPECT_FALSE(threshold.addNeighbour(2.0, 2.0, 0.0, -2.0));  // turned by 2°
  for (int i = 0; i < 4; ++i) threshold.addNeighbour(2.0, 2.0, 0.01, 0.2);
  EXPECT_FALSE(threshold.offsetNoise());        // four walls are too few
  threshold.addNeighbour(2.0, 0.5, 0.01, 0.2);  // its longest piece too short for its angle
  EXPECT_TRUE(threshold.offsetNoise());
  EXPECT_FALSE(threshold.angleNoise());
  EXPECT_EQ(threshold.thresholds(0.0).angle_deg, 1.5);
}

TEST(DeviationThreshold, FixedThresholdsAreTheOptionsOwn) {
  DeviationOptions options;
  options.shift_m = 0.05;
  options.angle_deg = 2.0;
  const WallThresholds t = DeviationThreshold::fixed(options);
  EXPECT_EQ(t.shift_m, 0.05);
  EXPECT_EQ(t.angle_deg, 2.0);
  options.min_noise_walls = 3;  // never fewer than four: the placement fitted three numbers
  DeviationThreshold threshold(options);
  for (int i = 0; i < 3; ++i) threshold.addNeighbour(2.0, 2.0, 0.01, 0.2);
  EXPECT_FALSE(threshold.offsetNoise());
}

}  // namespace
}  // namespace isg::slam
