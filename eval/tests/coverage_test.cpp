#include "eval/coverage.hpp"

#include <gtest/gtest.h>

namespace isg::eval {
namespace {

common::Trajectory stamps(double from, double to, double step) {
  common::Trajectory t;
  for (double s = from; s <= to + 1e-9; s += step) {
    common::StampedPose p;
    p.t = s;
    t.push_back(p);
  }
  return t;
}

TEST(Coverage, LocalizedAfterAQuarterOfTheRun) {
  // Ground truth 10 … 50 s; the estimate starts at 20 s: 10 s to localize, 75 % localized.
  const Coverage c = localizationCoverage(stamps(10, 50, 0.01), stamps(20, 50, 0.1));
  EXPECT_TRUE(c.localized);
  EXPECT_NEAR(c.time_to_first, 10.0, 1e-9);
  EXPECT_NEAR(c.share, 0.75, 1e-9);
}

TEST(Coverage, TimeLostIsNotLocalized) {
  // Ground truth 0 … 40 s; rows 10 … 20 s, lost 20 … 25 s, rows 25 … 35 s, lost to the end.
  common::Trajectory estimate = stamps(10, 20, 0.1);
  const common::Trajectory later = stamps(25, 35, 0.1);
  estimate.insert(estimate.end(), later.begin(), later.end());
  const Coverage c = localizationCoverage(stamps(0, 40, 0.01), estimate);
  EXPECT_NEAR(c.time_to_first, 10.0, 1e-9);
  EXPECT_NEAR(c.lost_seconds, 10.0, 1e-6);
  EXPECT_NEAR(c.share, 20.0 / 40.0, 1e-6);
}

TEST(Coverage, NeverLocalized) {
  const Coverage c = localizationCoverage(stamps(0, 30, 0.01), {});
  EXPECT_FALSE(c.localized);
  EXPECT_EQ(c.share, 0.0);
}

}  // namespace
}  // namespace isg::eval
