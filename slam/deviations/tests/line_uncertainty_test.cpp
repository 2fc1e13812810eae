// The fitted line's covariance against hand calculations.
#include "slam/deviations/line_uncertainty.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace isg::slam {
namespace {

TEST(LineUncertainty, TwoEndsOfAWallGiveTheTextbookVariances) {
  // Ends at s = ±2 on the line, equal weights, σ = 1 cm: (JᵀJ)⁻¹ = diag(1/2, 1/8).
  const double sigma = 0.01;
  const Eigen::Matrix2d covariance =
      lineCovariance({{{-2.0, 0.1}, 1.0}, {{2.0, 0.1}, 1.0}}, 0.1, 0.0, sigma);
  EXPECT_NEAR(covariance(0, 0), sigma * sigma / 2.0, 1e-12);
  EXPECT_NEAR(covariance(1, 1), sigma * sigma / 8.0, 1e-12);
  EXPECT_NEAR(covariance(0, 1), 0.0, 1e-15);
  // The weights' scale does not change it.
  EXPECT_NEAR(lineCovariance({{{-2.0, 0.1}, 7.0}, {{2.0, 0.1}, 7.0}}, 0.1, 0.0, sigma)(1, 1),
              sigma * sigma / 8.0, 1e-12);
}

TEST(LineUncertainty, EndsThatScatterMoreThanTheirSigmaSetIt) {
  // Six ends at s = −2, −2, 0, 0, 2, 2 alternately 3 cm above and below the line o = 0: the
  // scatter's variance 0.03² · 6/4 = 1.35e-3 exceeds 1 cm²; (JᵀJ)⁻¹ = diag(1/6, 1/16).
  std::vector<std::pair<Eigen::Vector2d, double>> ends;
  for (const double s : {-2.0, 0.0, 2.0}) {
    ends.push_back({{s, 0.03}, 1.0});
    ends.push_back({{s, -0.03}, 1.0});
  }
  const Eigen::Matrix2d covariance = lineCovariance(ends, 0.0, 0.0, 0.01);
  const double variance = 0.03 * 0.03 * 6.0 / 4.0;
  EXPECT_NEAR(covariance(0, 0), variance / 6.0, 1e-12);
  EXPECT_NEAR(covariance(1, 1), variance / 16.0, 1e-12);
  // Four ends (two per parameter) say nothing of the scatter: σ stands. At s = −2, −2, 0, 0:
  // JᵀJ = [[4, −4], [−4, 8]], whose inverse's first entry is 8 / 16.
  ends.resize(4);
  EXPECT_NEAR(lineCovariance(ends, 0.0, 0.0, 0.01)(0, 0), 0.01 * 0.01 / 2.0, 1e-12);
}

TEST(LineUncertainty, EndsAtOnePlaceLeaveTheSlopeUnknown) {
  const Eigen::Matrix2d covariance =
      lineCovariance({{{1.0, 0.0}, 1.0}, {{1.0, 0.0}, 1.0}}, 0.0, 0.0, 0.01);
  EXPECT_NEAR(covariance(0, 0), 1e-4, 1e-15);
  EXPECT_GE(covariance(1, 1), 1e6);
}

}  // namespace
}  // namespace isg::slam
