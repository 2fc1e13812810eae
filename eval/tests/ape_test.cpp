#include "eval/ape.hpp"

#include <gtest/gtest.h>
#include <numbers>

#include <random>

namespace isg::eval {
namespace {

common::StampedPose pose(double t, double x, double y, double z, double yaw = 0.0) {
  common::StampedPose p;
  p.t = t;
  p.pose.translation() = Eigen::Vector3d(x, y, z);
  p.pose.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return p;
}

TEST(Statistics, HandComputed) {
  // Errors 1, 2, 3, 4: mean 2.5, median 2.5, sse 30, rmse √7.5, population std √1.25.
  const Statistics s = statistics({3, 1, 4, 2});
  EXPECT_EQ(s.count, 4);
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.median, 2.5);
  EXPECT_DOUBLE_EQ(s.sse, 30.0);
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(7.5));
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(1.25));
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 4.0);
  EXPECT_DOUBLE_EQ(statistics({5, 1, 3}).median, 3.0);
}

TEST(Association, NearestWithinTheWindowNoInterpolation) {
  common::Trajectory ref, est;
  for (int i = 0; i < 10; ++i) ref.push_back(pose(i * 0.1, i, 0, 0));  // 10 Hz
  est.push_back(pose(0.004, 0, 0, 0));                                 // 4 ms from 0.0: kept
  est.push_back(pose(0.15, 0, 0, 0));    // 50 ms from both neighbours: dropped
  est.push_back(pose(0.309, 0, 0, 0));   // 9 ms from 0.3: kept
  est.push_back(pose(0.5111, 0, 0, 0));  // 11.1 ms: dropped
  const Association a = associate(ref, est, 0.01);
  EXPECT_EQ(a.estimate, (std::vector<int>{0, 2}));
  EXPECT_EQ(a.reference, (std::vector<int>{0, 3}));
}

TEST(Association, GapsDuplicatesAndUnequalRates) {
  common::Trajectory ref, est;
  // Reference at 100 Hz with a gap between 0.5 and 1.0 s; a duplicated stamp at 0.2 s.
  for (int i = 0; i <= 50; ++i) ref.push_back(pose(i * 0.01, 0, 0, 0));
  ref.insert(ref.begin() + 21, pose(0.2, 9, 9, 9));
  for (int i = 100; i <= 150; ++i) ref.push_back(pose(i * 0.01, 0, 0, 0));
  // Estimate at 10 Hz: 0.0 … 1.5 s.
  for (int i = 0; i <= 15; ++i) est.push_back(pose(i * 0.1, 0, 0, 0));
  const Association a = associate(ref, est, 0.01);
  // 0.6 … 0.9 fall in the gap: 16 - 4 = 12 pairs.
  EXPECT_EQ(a.estimate.size(), 12u);
  // The duplicate: the first of the two stamps at 0.2 s is taken, as numpy's argmin does.
  EXPECT_EQ(a.reference[2], 20);
  // A shorter reference is the one iterated: indices come back in the right roles.
  const Association b = associate(est, ref, 0.01);
  EXPECT_EQ(b.reference.size(), 12u);
  EXPECT_EQ(b.estimate[2], 20);
}

TEST(Alignment, RecoversAKnownSimilarity) {
  std::mt19937 rng(1);
  std::normal_distribution<double> n(0, 3);
  Similarity truth;
  truth.rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  truth.translation = Eigen::Vector3d(4, -2, 1);
  truth.scale = 1.7;
  std::vector<Eigen::Vector3d> from, to;
  for (int i = 0; i < 50; ++i) {
    from.emplace_back(n(rng), n(rng), n(rng));
    to.push_back(truth.apply(from.back()));
  }
  const Similarity sim3 = umeyama(from, to, true);
  EXPECT_NEAR((sim3.rotation - truth.rotation).norm(), 0.0, 1e-10);
  EXPECT_NEAR((sim3.translation - truth.translation).norm(), 0.0, 1e-10);
  EXPECT_NEAR(sim3.scale, 1.7, 1e-10);
  // Without scale, a rigid transform is recovered exactly.
  truth.scale = 1.0;
  for (std::size_t i = 0; i < from.size(); ++i) to[i] = truth.apply(from[i]);
  const Similarity se3 = umeyama(from, to, false);
  EXPECT_NEAR((se3.rotation - truth.rotation).norm(), 0.0, 1e-10);
  EXPECT_DOUBLE_EQ(se3.scale, 1.0);
  EXPECT_THROW(umeyama({from[0], from[1]}, {to[0], to[1]}, false), std::invalid_argument);
}

TEST(Ape, HandComputedWithoutAlignment) {
  common::Trajectory ref, est;
  for (int i = 0; i < 4; ++i) ref.push_back(pose(i, i, 0, 0));
  // Estimate off by 0.1, 0.2 (in y), 0.3 (in z), and turned by 90° at the last pose.
  est.push_back(pose(0, 0, 0.1, 0));
  est.push_back(pose(1, 1, 0.2, 0));
  est.push_back(pose(2, 2, 0, 0.3));
  est.push_back(pose(3, 3, 0, 0, std::numbers::pi / 2));
  const ErrorResult r = absolutePoseError(ref, est, {});
  EXPECT_EQ(r.translation_stats.count, 4);
  EXPECT_NEAR(r.translation_stats.max, 0.3, 1e-12);
  EXPECT_NEAR(r.translation_stats.rmse, std::sqrt((0.01 + 0.04 + 0.09) / 4), 1e-12);
  EXPECT_NEAR(r.rotation_stats.max, 90.0, 1e-9);
  EXPECT_FALSE(r.alignment);
  // Projected onto xy, z no longer counts: the third error vanishes.
  ErrorOptions xy;
  xy.project_xy = true;
  EXPECT_NEAR(absolutePoseError(ref, est, xy).translation[2], 0.0, 1e-12);
}

TEST(Ape, AlignmentRemovesAnUnknownFrame) {
  // The estimate is the reference seen from another frame (yaw 1 rad, moved): APE without
  // alignment is large, with SE(3) alignment zero.
  common::Trajectory ref, est;
  Eigen::Isometry3d M_T_B = Eigen::Isometry3d::Identity();
  M_T_B.linear() = Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  M_T_B.translation() = Eigen::Vector3d(3, 1, 0);
  for (int i = 0; i < 30; ++i) {
    ref.push_back(pose(i * 0.1, std::cos(i * 0.2) * 3, std::sin(i * 0.2) * 2, 0.1 * i, i * 0.2));
    common::StampedPose e = ref.back();
    e.pose = M_T_B * e.pose;
    est.push_back(e);
  }
  EXPECT_GT(absolutePoseError(ref, est, {}).translation_stats.rmse, 1.0);
  ErrorOptions se3;
  se3.align = Alignment::kSE3;
  const ErrorResult aligned = absolutePoseError(ref, est, se3);
  EXPECT_LT(aligned.translation_stats.max, 1e-9);
  EXPECT_LT(aligned.rotation_stats.max, 1e-6);
}

TEST(Ape, APlacementIsTheSameAsAPlacedCopy) {
  // Dead reckoning judged from the true start: the odometry placed by B_T_M as it is compared,
  // the same numbers as comparing a placed copy of it.
  common::Trajectory ref, odometry, placed;
  Eigen::Isometry3d B_T_M = Eigen::Isometry3d::Identity();
  B_T_M.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  B_T_M.translation() = Eigen::Vector3d(4, -2, 0.5);
  for (int i = 0; i < 20; ++i) {
    ref.push_back(pose(i * 0.1, 0.3 * i, std::sin(i * 0.3), 0.0, 0.1 * i));
    odometry.push_back(pose(i * 0.1, 0.31 * i, 0.1 * i, 0.01 * i, 0.12 * i));
    placed.push_back({odometry.back().t, B_T_M * odometry.back().pose});
  }
  ErrorOptions xy;
  xy.project_xy = true;
  const ErrorResult copy = absolutePoseError(ref, placed, xy);
  const ErrorResult in_place = absolutePoseError(ref, odometry, xy, B_T_M);
  EXPECT_EQ(in_place.translation, copy.translation);
  EXPECT_EQ(in_place.rotation_deg, copy.rotation_deg);
  EXPECT_GT(in_place.translation_stats.rmse, 1.0);  // the placement counts: far from the start
  EXPECT_EQ(absolutePoseError(ref, odometry, xy, std::nullopt).translation,
            absolutePoseError(ref, odometry, xy).translation);
}

TEST(Rpe, ConstantOffsetHasNoRelativeError) {
  common::Trajectory ref, est;
  for (int i = 0; i < 10; ++i) {
    ref.push_back(pose(i, i, 0, 0));
    est.push_back(pose(i, i + 5, 2, 0));  // shifted, not drifting
  }
  est[6].pose.translation().x() += 0.5;  // one bad pose: two bad pairs
  const ErrorResult r = relativePoseError(ref, est, {});
  EXPECT_EQ(r.translation_stats.count, 9);
  EXPECT_NEAR(r.translation[4], 0.0, 1e-12);
  EXPECT_NEAR(r.translation[5], 0.5, 1e-12);
  EXPECT_NEAR(r.translation[6], 0.5, 1e-12);
}

}  // namespace
}  // namespace isg::eval
