#include "eval/floor_plan_score.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace isg::eval {
namespace {

common::StampedPose at(double t, double x, double y, double z = 0.0) {
  common::StampedPose pose;
  pose.t = t;
  pose.pose.translation() = Eigen::Vector3d(x, y, z);
  return pose;
}

// The benchmark's constants: 100 at 0 m, 1 at 10 m.
TEST(FloorPlanScore, ScoresAHundredAtZeroAndOneAtTenMetres) {
  std::vector<common::StampedPose> reference, exact, ten_off;
  for (int k = 0; k <= 100; ++k) {
    reference.push_back(at(0.1 * k, 0.1 * k, 0.0));
    exact.push_back(at(0.1 * k, 0.1 * k, 0.0));
    ten_off.push_back(at(0.1 * k, 0.1 * k, 10.0));
  }
  EXPECT_DOUBLE_EQ(floorPlanScore(reference, exact).score, 100.0);  // the cap is never passed
  EXPECT_NEAR(floorPlanScore(reference, ten_off).score, 1.0, 1e-12);
}

TEST(FloorPlanScore, ByHandOnATenSecondWalk) {
  // Reference at 10 Hz for 10 s along x; the estimate 0.1 m off in y at every stamp from 0 s on.
  std::vector<common::StampedPose> reference, estimate;
  for (int k = 0; k <= 100; ++k) {
    reference.push_back(at(0.1 * k, 0.1 * k, 0.0));
    estimate.push_back(at(0.1 * k, 0.1 * k, 0.1));
  }
  const FloorPlanScore score = floorPlanScore(reference, estimate);
  // Scored: the 51 poses from 5.0 s on; each 100 · e^(−0.046051701859880917).
  EXPECT_EQ(score.poses, 51);
  EXPECT_EQ(score.associated, 51);
  EXPECT_DOUBLE_EQ(score.coverage, 1.0);
  EXPECT_NEAR(score.score, 100.0 * std::exp(-0.046051701859880917), 1e-9);
  ASSERT_EQ(score.per_pose.size(), 51u);
  EXPECT_DOUBLE_EQ(score.per_pose.front().t, 5.0);
  EXPECT_NEAR(score.per_pose.front().error, 0.1, 1e-12);
}

TEST(FloorPlanScore, TheFirstFiveSecondsOfTheRunAreNotScored) {
  // 10 m off before 5 s, exact after: 100.
  std::vector<common::StampedPose> reference, estimate;
  for (int k = 0; k <= 100; ++k) {
    reference.push_back(at(0.1 * k, 0.0, 0.0));
    estimate.push_back(at(0.1 * k, 0.0, k < 50 ? 10.0 : 0.0));
  }
  EXPECT_DOUBLE_EQ(floorPlanScore(reference, estimate).score, 100.0);
  // In the benchmark's clock the recording starts at 10 000 s and its reference later (here at
  // 10 003.2 s): scored from 10 005 s on, not 5 s after the reference's first stamp.
  std::vector<common::StampedPose> shifted;
  for (int k = 0; k <= 100; ++k) shifted.push_back(at(10003.2 + 0.1 * k, 0.0, 0.0));
  const FloorPlanScore benchmark = floorPlanScore(shifted, shifted);
  EXPECT_DOUBLE_EQ(benchmark.run_start, 10000.0);
  EXPECT_EQ(benchmark.poses, 83);  // 10 005.0 … 10 013.2
  FloorPlanScoreOptions given;
  given.run_start = 10003.2;
  EXPECT_EQ(floorPlanScore(shifted, shifted, given).poses, 51);
}

TEST(FloorPlanScore, HeightIsNotScored) {
  std::vector<common::StampedPose> reference, estimate;
  for (int k = 0; k <= 100; ++k) {
    reference.push_back(at(0.1 * k, 0.1 * k, 0.0, 1.2));
    estimate.push_back(at(0.1 * k, 0.1 * k, 0.0, 3.0));
  }
  EXPECT_DOUBLE_EQ(floorPlanScore(reference, estimate).score, 100.0);
}

TEST(FloorPlanScore, PosesAreAssociatedAsEvoDoesWithinTenMilliseconds) {
  std::vector<common::StampedPose> reference, near, far;
  for (int k = 0; k <= 1000; ++k) {
    reference.push_back(at(0.1 * k, 0.0, 0.0));
    near.push_back(at(0.1 * k + 0.009, 0.0, 0.0));
    far.push_back(at(0.1 * k + 0.011, 0.0, 0.0));
  }
  EXPECT_DOUBLE_EQ(floorPlanScore(reference, near).coverage, 1.0);
  const FloorPlanScore missed = floorPlanScore(reference, far);
  EXPECT_EQ(missed.associated, 0);
  EXPECT_EQ(missed.score, 0.0);
  // No interpolation: an estimate at 10 Hz against a reference at 50 Hz covers a fifth.
  std::vector<common::StampedPose> dense;
  for (int k = 0; k <= 5000; ++k) dense.push_back(at(0.02 * k, 0.0, 0.0));
  EXPECT_NEAR(floorPlanScore(dense, reference).coverage, 951.0 / 4751.0, 1e-12);
  EXPECT_EQ(floorPlanScore(dense, reference).score, 0.0);
}

TEST(FloorPlanScore, UnderNinetyNinePercentCoveredScoresZero) {
  std::vector<common::StampedPose> reference, estimate;
  for (int k = 0; k <= 1000; ++k) reference.push_back(at(0.1 * k, 0.0, 0.0));  // 100 s
  // Exact from 5 s on, but lost for 1 s (10 poses of the 951 scored): 98.9 % covered.
  for (int k = 0; k <= 1000; ++k) {
    if (k >= 400 && k < 410) continue;
    estimate.push_back(at(0.1 * k, 0.0, 1.0));
  }
  const FloorPlanScore lost = floorPlanScore(reference, estimate);
  EXPECT_EQ(lost.poses, 951);
  EXPECT_NEAR(lost.coverage, 941.0 / 951.0, 1e-12);
  EXPECT_EQ(lost.score, 0.0);
  // Lost for 0.5 s (5 poses): 99.5 % covered; the mean is over the associated poses.
  estimate.clear();
  for (int k = 0; k <= 1000; ++k) {
    if (k >= 400 && k < 405) continue;
    estimate.push_back(at(0.1 * k, 0.0, 1.0));
  }
  const FloorPlanScore brief = floorPlanScore(reference, estimate);
  EXPECT_NEAR(brief.coverage, 946.0 / 951.0, 1e-12);
  EXPECT_NEAR(brief.score, 100.0 * std::exp(-0.46051701859880917), 1e-9);
  // No estimate at all, and no reference: 0 of 0.
  EXPECT_EQ(floorPlanScore(reference, {}).score, 0.0);
  EXPECT_EQ(floorPlanScore({}, estimate).poses, 0);
}

TEST(FloorPlanScore, ARunIsScoredOnItsEstimateAtTheTruthsStamps) {
  // A run's estimate at 10 Hz, its truth at 50 Hz: resampled, every stamp is estimated.
  std::vector<common::StampedPose> truth, estimate;
  for (int k = 0; k <= 500; ++k) truth.push_back(at(0.02 * k, 0.02 * k, 0.0));
  for (int k = 0; k <= 100; ++k) estimate.push_back(at(0.1 * k, 0.1 * k, 0.1));
  const common::Trajectory resampled = estimateAtStamps(truth, estimate);
  ASSERT_EQ(resampled.size(), truth.size());
  EXPECT_NEAR(resampled[3].pose.translation().x(), 0.06, 1e-12);
  EXPECT_NEAR(runFloorPlanScore(truth, estimate).score, 100.0 * std::exp(-0.046051701859880917),
              1e-9);
  // Across a gap longer than 0.25 s nothing is made up: those stamps stay without an estimate.
  estimate.erase(estimate.begin() + 60, estimate.begin() + 63);  // 5.9 … 6.3 s
  EXPECT_EQ(estimateAtStamps(truth, estimate).size(), truth.size() - 19);
}

}  // namespace
}  // namespace isg::eval
