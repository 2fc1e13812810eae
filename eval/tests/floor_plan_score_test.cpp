#include "eval/floor_plan_score.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace isg::eval {
namespace {

common::StampedPose at(double t, double x, double y) {
  common::StampedPose pose;
  pose.t = t;
  pose.pose.translation() = Eigen::Vector3d(x, y, 0.0);
  return pose;
}

TEST(FloorPlanScore, ByHandOnATenSecondWalk) {
  // Reference at 10 Hz for 10 s along x; the estimate 0.1 m off in y at every stamp from 0 s on.
  std::vector<common::StampedPose> reference, estimate;
  for (int k = 0; k <= 100; ++k) {
    reference.push_back(at(0.1 * k, 0.1 * k, 0.0));
    estimate.push_back(at(0.1 * k, 0.1 * k, 0.1));
  }
  const FloorPlanScore score = floorPlanScore(reference, estimate);
  // Scored: the 51 poses from 5.0 s on; each 100 · e^(−0.04605).
  EXPECT_EQ(score.poses, 51);
  EXPECT_DOUBLE_EQ(score.coverage, 1.0);
  EXPECT_NEAR(score.score, 100.0 * std::exp(-0.04605), 1e-9);
  // A denser reference (50 Hz) is met by the estimate interpolated between its rows.
  std::vector<common::StampedPose> dense;
  for (int k = 0; k <= 500; ++k) dense.push_back(at(0.02 * k, 0.02 * k, 0.0));
  EXPECT_NEAR(floorPlanScore(dense, estimate).score, 100.0 * std::exp(-0.04605), 1e-9);
}

TEST(FloorPlanScore, UnderNinetyNinePercentEstimatedScoresZero) {
  std::vector<common::StampedPose> reference, estimate;
  for (int k = 0; k <= 1000; ++k) reference.push_back(at(0.1 * k, 0.0, 0.0));  // 100 s
  // Exact from 5 s on, but lost for 1 s (10 poses of the 951 scored): 98.9 % covered.
  for (int k = 0; k <= 1000; ++k) {
    if (k >= 400 && k < 410) continue;
    estimate.push_back(at(0.1 * k, 0.0, 0.0));
  }
  const FloorPlanScore lost = floorPlanScore(reference, estimate);
  EXPECT_EQ(lost.poses, 951);
  EXPECT_NEAR(lost.coverage, 941.0 / 951.0, 1e-12);
  EXPECT_EQ(lost.score, 0.0);
  // Lost for 0.5 s (5 poses; the gap 0.6 s > max_gap): 99.5 % covered, each missing pose 0.
  estimate.clear();
  for (int k = 0; k <= 1000; ++k) {
    if (k >= 400 && k < 405) continue;
    estimate.push_back(at(0.1 * k, 0.0, 0.0));
  }
  const FloorPlanScore brief = floorPlanScore(reference, estimate);
  EXPECT_NEAR(brief.coverage, 946.0 / 951.0, 1e-12);
  EXPECT_NEAR(brief.score, 100.0 * 946.0 / 951.0, 1e-9);
  // No estimate at all, and no reference: 0 of 0.
  EXPECT_EQ(floorPlanScore(reference, {}).score, 0.0);
  EXPECT_EQ(floorPlanScore({}, estimate).poses, 0);
}

}  // namespace
}  // namespace isg::eval
