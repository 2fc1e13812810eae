#include "common/tum.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <numbers>

#include <cmath>
#include <cstring>
#include <random>

namespace isg::common {
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

// quantised() must give, bit for bit, what a TUM file gives back: the live loop relies on it to
// see the numbers a replay of the recorded dataset sees.
TEST(Tum, QuantisedIsTheTextRoundTripBitForBit) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> time(0.0, 5000.0), coordinate(-300.0, 300.0),
      angle(-std::numbers::pi, std::numbers::pi);
  Trajectory t;
  for (int i = 0; i < 20000; ++i) {
    StampedPose p;
    p.t = i % 3 == 0 ? i * 0.01 : time(rng);  // rates' stamps and arbitrary ones
    p.pose.translation() = Eigen::Vector3d(coordinate(rng), coordinate(rng), coordinate(rng) / 100);
    p.pose.linear() = (Eigen::AngleAxisd(angle(rng), Eigen::Vector3d::UnitZ()) *
                       Eigen::AngleAxisd(angle(rng) / 20, Eigen::Vector3d::UnitX()))
                          .toRotationMatrix();
    t.push_back(p);
  }
  // Exact ties of the decimal rounding (ties go to even) and signed zeros.
  for (double v : {0.0009765625, -0.0009765625, 0.0000005, -0.0000004, 2.5e-7, 1.0 / 1024}) {
    StampedPose p;
    p.t = std::abs(v);
    p.pose.translation() = Eigen::Vector3d(v, -v, v * 3);
    t.push_back(p);
  }
  // One file per pose: the stamps are in no order, and a TUM file must be.
  Trajectory text;
  for (const auto& p : t) text.push_back(parseTum(toTumText(Trajectory{p}), "x.tum").front());
  const Trajectory numbers = quantised(t);
  ASSERT_EQ(numbers.size(), text.size());
  int differing = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const bool same = std::memcmp(&numbers[i].t, &text[i].t, sizeof(double)) == 0 &&
                      std::memcmp(numbers[i].pose.matrix().data(), text[i].pose.matrix().data(),
                                  16 * sizeof(double)) == 0;
    differing += !same;
  }
  EXPECT_EQ(differing, 0);
}

}  // namespace
}  // namespace isg::common
