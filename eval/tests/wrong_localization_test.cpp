#include "eval/wrong_localization.hpp"

#include <gtest/gtest.h>

namespace isg::eval {
namespace {

// Ground truth along x at 1 m/s, every 0.1 s from 0 to 60 s.
common::Trajectory truth() {
  common::Trajectory t;
  for (int i = 0; i <= 600; ++i) {
    common::StampedPose p;
    p.t = 0.1 * i;
    p.pose.translation() = Eigen::Vector3d(p.t, 0.0, 0.0);
    t.push_back(p);
  }
  return t;
}

// The estimate from `from` to `to` seconds, off by `offset(t)` metres in y and `z` in height.
template <typename Offset>
common::Trajectory estimate(double from, double to, Offset offset, double z = 0.6) {
  common::Trajectory t;
  for (int i = int(from * 10 + 0.5); i <= int(to * 10 + 0.5); ++i) {
    common::StampedPose p;
    p.t = 0.1 * i;
    p.pose.translation() = Eigen::Vector3d(p.t, offset(p.t), z);  // within 1 m: the same floor
    t.push_back(p);
  }
  return t;
}

TEST(WrongLocalization, RightAllAlong) {
  const auto w = wrongLocalization(truth(), estimate(10, 60, [](double) { return 0.3; }));
  EXPECT_FALSE(w.wrong);
  EXPECT_DOUBLE_EQ(w.seconds, 0.0);
  EXPECT_NEAR(w.max_error, 0.3, 1e-9);
}

TEST(WrongLocalization, RightInThePlaneOnAnotherFloorIsWrong) {
  // 3.2 m up: a storey above, however right x and y are.
  const auto w = wrongLocalization(truth(), estimate(
                                                10, 60, [](double) { return 0.0; }, 3.2));
  EXPECT_TRUE(w.wrong);
  EXPECT_NEAR(w.seconds, 50.0, 1e-6);
  EXPECT_NEAR(w.max_height_error, 3.2, 1e-9);
  EXPECT_NEAR(w.max_error, 0.0, 1e-9);
  ASSERT_TRUE(w.first_wrong_at.has_value());
  EXPECT_NEAR(*w.first_wrong_at, 10.0, 1e-9);
  // 0.9 m off in height is still this floor.
  EXPECT_FALSE(wrongLocalization(truth(), estimate(
                                              10, 60, [](double) { return 0.0; }, 0.9))
                   .wrong);
}

TEST(WrongLocalization, ABriefExcursionIsNotWrong) {
  // 2 m off from 20.0 to 24.0 s inclusive: a 4 s stretch, under the 5 s of a wrong run.
  const auto w = wrongLocalization(
      truth(), estimate(10, 60, [](double t) { return t > 19.95 && t < 24.05 ? 2.0 : 0.0; }));
  EXPECT_FALSE(w.wrong);
  EXPECT_NEAR(w.seconds, 4.0, 1e-9);
  EXPECT_NEAR(w.longest, 4.0, 1e-9);
  EXPECT_FALSE(w.first_wrong_at);
}

TEST(WrongLocalization, SecondsOnEndOffIsWrong) {
  // 1.5 m off from 30 s to the end: 30 s wrong, from 30 s on.
  const auto w =
      wrongLocalization(truth(), estimate(10, 60, [](double t) { return t > 29.95 ? 1.5 : 0.1; }));
  EXPECT_TRUE(w.wrong);
  EXPECT_NEAR(w.seconds, 30.0, 1e-9);
  ASSERT_TRUE(w.first_wrong_at);
  EXPECT_NEAR(*w.first_wrong_at, 30.0, 1e-9);
}

TEST(WrongLocalization, TimeWithoutRowsIsNotCounted) {
  // Off 3 s, then no rows for 10 s (lost), then off 3 s more: two stretches of 3 s, not wrong.
  common::Trajectory e = estimate(10, 13, [](double) { return 3.0; });
  const common::Trajectory later = estimate(23, 26, [](double) { return 3.0; });
  e.insert(e.end(), later.begin(), later.end());
  const auto w = wrongLocalization(truth(), e);
  EXPECT_FALSE(w.wrong);
  EXPECT_NEAR(w.seconds, 6.0, 1e-9);
  EXPECT_NEAR(w.longest, 3.0, 1e-9);
}

TEST(WrongLocalization, NothingToJudge) {
  EXPECT_FALSE(wrongLocalization({}, estimate(0, 1, [](double) { return 9.0; })).wrong);
  EXPECT_FALSE(wrongLocalization(truth(), {}).wrong);
}

}  // namespace
}  // namespace isg::eval
