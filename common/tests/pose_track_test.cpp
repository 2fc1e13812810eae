#include "common/pose_track.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "common/pose_interpolation.hpp"
#include "common/tum.hpp"

namespace isg::common {
namespace {

bool sameBits(const StampedPose& a, const StampedPose& b) {
  return std::memcmp(&a.t, &b.t, sizeof(double)) == 0 &&
         std::memcmp(a.pose.matrix().data(), b.pose.matrix().data(), 16 * sizeof(double)) == 0;
}

// Poses a walk makes (turns about z, small tilts), with rotations about one axis only (zeros in
// the quaternion, some of them negative) and the odd far-away or tiny coordinate.
Trajectory walk(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> angle(-3.14, 3.14), tilt(-0.05, 0.05), x(-60.0, 60.0);
  Trajectory out;
  for (int i = 0; i < n; ++i) {
    StampedPose p;
    p.t = 1.7e9 + i * 0.01 + 1e-12 * i;
    const double yaw = angle(rng);
    if (i % 5 == 0) {
      p.pose.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    } else if (i % 5 == 1) {
      p.pose.linear() = Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitX()).toRotationMatrix();
    } else {
      p.pose.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                         Eigen::AngleAxisd(tilt(rng), Eigen::Vector3d::UnitY()) *
                         Eigen::AngleAxisd(tilt(rng), Eigen::Vector3d::UnitX()))
                            .toRotationMatrix();
    }
    p.pose.translation() = Eigen::Vector3d(x(rng), i % 7 == 0 ? -1e-9 : x(rng), 0.445);
    if (i % 11 == 0) p.pose.translation().x() = 3.0e5 + x(rng);
    out.push_back(p);
  }
  return out;
}

TEST(PoseTrack, PushedQuantisedItHoldsBitForBitWhatQuantiseMakes) {
  const Trajectory raw = walk(20000, 1);
  const Trajectory rounded = quantised(raw);
  PoseTrack track;
  track.reserve(raw.size());
  for (const auto& pose : raw) track.pushQuantised(pose);
  ASSERT_EQ(track.size(), raw.size());
  for (std::size_t i = 0; i < raw.size(); ++i) {
    ASSERT_TRUE(sameBits(track[i], rounded[i])) << "pose " << i;
  }
  // The text of the rounded poses too, signs of zero included (the poses tried hold some).
  const std::string text = toTumText(rounded);
  EXPECT_GT(std::count(text.begin(), text.end(), '-'), 0);
  std::size_t negative_zeros = 0;
  for (auto at = text.find(" -0.000000000"); at != std::string::npos;
       at = text.find(" -0.000000000", at + 1)) {
    ++negative_zeros;
  }
  EXPECT_GT(negative_zeros, 100u);
  EXPECT_EQ(toTumText(track.toTrajectory()), text);
  // 36 bytes a pose, against a StampedPose's 144; a position over 2147 m from the first one
  // (1 in 11 of those tried is 300 km out, the first among them) is kept whole beside its row.
  std::size_t far = 0;
  for (const auto& pose : raw) {
    far += std::abs(pose.pose.translation().x() - raw[0].pose.translation().x()) > 2147.0;
  }
  EXPECT_EQ(far, raw.size() - (raw.size() + 10) / 11);
  EXPECT_GE(track.bytes(), 36u * raw.size() + 24u * far);
  EXPECT_LE(track.bytes(), 36u * raw.size() + 2 * 24u * far);  // the side vector's growth
  EXPECT_EQ(sizeof(StampedPose), 144u);
}

TEST(PoseTrack, AWalkFarFromThePlansOriginStaysCompact) {
  // A walk within ±60 m, 8 km out in x and y (the far-from-origin reference worlds).
  Trajectory raw;
  for (auto pose : walk(3000, 4)) {
    if (pose.pose.translation().x() > 1e5) pose.pose.translation().x() -= 3.0e5;
    pose.pose.translation() += Eigen::Vector3d(8000.0, -8000.0, 0.0);
    raw.push_back(pose);
  }
  const Trajectory rounded = quantised(raw);
  PoseTrack track;
  track.reserve(raw.size());
  for (const auto& pose : raw) track.pushQuantised(pose);
  const PoseTrack copied(rounded);
  for (std::size_t i = 0; i < raw.size(); ++i) {
    ASSERT_TRUE(sameBits(track[i], rounded[i])) << i;
    ASSERT_TRUE(sameBits(copied[i], rounded[i])) << i;
  }
  EXPECT_EQ(track.bytes(), 36u * raw.size());
}

TEST(PoseTrack, PositionsThatDoNotFitAreKeptWholeAndExact) {
  StampedPose first, far, odd, missing;
  first.pose.translation() = Eigen::Vector3d(1.0, 2.0, 3.0);
  far.pose.translation() = Eigen::Vector3d(1.0, 2.0 + 2148.0, -0.0);  // over 2147 m in y
  odd.pose.translation() = Eigen::Vector3d(1.0 + 1e-7, 2.0, 3.0);     // finer than a step
  missing.pose.translation() = Eigen::Vector3d(std::nan(""), 2.0, 3.0);
  const PoseTrack track({first, far, odd, missing, first});
  for (int i : {0, 1, 2, 4}) {
    const StampedPose expected = i == 1 ? far : i == 2 ? odd : first;
    EXPECT_TRUE(sameBits(track[std::size_t(i)], expected)) << i;
  }
  EXPECT_TRUE(std::isnan(track[3].pose.translation().x()));
  EXPECT_TRUE(std::signbit(track[1].pose.translation().z()));
  EXPECT_GE(track.bytes(), 36u * 5 + 24u * 3);
  EXPECT_LE(track.bytes(), 36u * 5 + 24u * 4);
}

TEST(PoseTrack, AnyPoseReadsBackExactlyAndRoundedOnesStayCompact) {
  const Trajectory raw = walk(5000, 2);
  const PoseTrack exact(raw);  // unrounded rotations: each kept whole
  for (std::size_t i = 0; i < raw.size(); ++i) ASSERT_TRUE(sameBits(exact[i], raw[i])) << i;
  const Trajectory rounded = quantised(raw);
  const PoseTrack compact(rounded);
  for (std::size_t i = 0; i < raw.size(); ++i) ASSERT_TRUE(sameBits(compact[i], rounded[i])) << i;
  // Rounded poses rebuild from their nine decimals but where normalising moved one (~1.5 %).
  // (The positions 300 km from the first are kept whole in both: 24 bytes each, and up to as
  // much again of the side vector's growth.)
  const std::size_t positions = 24u * (raw.size() - (raw.size() + 10) / 11);
  EXPECT_LT(compact.bytes(), 36u * raw.size() + 2 * positions + 72u * raw.size() / 20);
  EXPECT_GT(exact.bytes(), 36u * raw.size() + positions + 72u * raw.size() * 9 / 10);
}

TEST(PoseTrack, NonFiniteRotationsAreKeptWhole) {
  StampedPose p;
  p.pose.linear()(0, 0) = std::nan("");
  const PoseTrack track({p});
  EXPECT_TRUE(std::isnan(track[0].pose.linear()(0, 0)));
  EXPECT_EQ(track[0].pose.linear()(1, 1), 1.0);
}

TEST(PoseSequence, ViewsBothKindsAlike) {
  const Trajectory rounded = quantised(walk(300, 3));
  const PoseTrack track(rounded);
  const PoseSequence of_vector(rounded), of_track(track);
  ASSERT_EQ(of_vector.size(), of_track.size());
  for (std::size_t i = 0; i < rounded.size(); ++i) {
    EXPECT_TRUE(sameBits(of_vector[i], of_track[i]));
    EXPECT_EQ(of_track.time(i), rounded[i].t);
    EXPECT_EQ(of_track.position(i), rounded[i].pose.translation());
  }
  // Its iterators serve the standard algorithms: the first pose at or after a time.
  const double t = rounded[123].t - 1e-6;
  const auto it = std::lower_bound(of_track.begin(), of_track.end(), t,
                                   [](const StampedPose& p, double s) { return p.t < s; });
  EXPECT_EQ(it - of_track.begin(), 123);
  EXPECT_EQ(it->t, rounded[123].t);
  EXPECT_TRUE(PoseSequence().empty());
  // Interpolation reads either the same.
  const double between = 0.5 * (rounded[40].t + rounded[41].t);
  const auto a = interpolatePose(rounded, between), b = interpolatePose(track, between);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(std::memcmp(a->matrix().data(), b->matrix().data(), 16 * sizeof(double)), 0);
  EXPECT_FALSE(interpolatePose(track, rounded.back().t + 1.0));
}

}  // namespace
}  // namespace isg::common
