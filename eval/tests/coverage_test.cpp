#include "eval/coverage.hpp"

#include <gtest/gtest.h>

namespace isg::eval {
namespace {

Trajectory stamps(double from, double to, double step) {
  Trajectory t;
  for (double s = from; s <= to + 1e-9; s += step) {
    StampedPose p;
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

TEST(Coverage, NeverLocalized) {
  const Coverage c = localizationCoverage(stamps(0, 30, 0.01), {});
  EXPECT_FALSE(c.localized);
  EXPECT_EQ(c.share, 0.0);
}

}  // namespace
}  // namespace isg::eval
