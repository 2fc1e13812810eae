#include "eval/tum.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace isg::eval {
namespace {

TEST(Tum, WritesAndReadsBack) {
  Trajectory t(2);
  t[0].t = 0.1;
  t[0].pose.translation() = Eigen::Vector3d(1, 2, 3);
  t[1].t = 12345.000000001;
  t[1].pose.linear() =
      Eigen::AngleAxisd(2.5, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const std::string text = toTumText(t);
  EXPECT_THAT(
      text, ::testing::StartsWith("0.100000000 1.000000 2.000000 3.000000 0.000000000 0.000000000 "
                                  "0.000000000 1.000000000\n"));
  const Trajectory back = parseTum("# comment\n\n" + text, "x.tum");
  ASSERT_EQ(back.size(), 2u);
  EXPECT_DOUBLE_EQ(back[1].t, 12345.000000001);
  EXPECT_NEAR((back[1].pose.linear() - t[1].pose.linear()).norm(), 0.0, 1e-8);
}

TEST(Tum, MalformedLineNamesFileAndLine) {
  try {
    parseTum("0 0 0 0 0 0 0 1\n1 2 3\n", "gt.tum");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "gt.tum: line 2: expected 8 numbers: t tx ty tz qx qy qz qw");
  }
}

}  // namespace
}  // namespace isg::eval
