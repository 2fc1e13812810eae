#include "sim/walk_path.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "common/angles.hpp"
#include "sim/smoothing_spline.hpp"

namespace isg::sim {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(SmoothingSpline, GivesBackALineExactlyAndACubicClosely) {
  std::vector<double> times, line, cubic;
  for (int i = 0; i <= 500; ++i) {
    const double t = 0.02 * i;  // 50 Hz over 10 s
    times.push_back(t);
    line.push_back(1.5 - 0.7 * t);
    cubic.push_back(0.01 * t * t * t - 0.2 * t * t + t);
  }
  const SmoothingSplineFit fit(times, 0.2, 1e-3);
  const UniformCubicSpline l = fit.fit(line), c = fit.fit(cubic);
  for (double t = 0.0; t <= 10.0; t += 0.013) {
    // A line has no second differences: the smoothness term does not pull at it.
    EXPECT_NEAR(l.at(t).value, 1.5 - 0.7 * t, 1e-9);
    EXPECT_NEAR(l.at(t).rate, -0.7, 1e-9);
    EXPECT_NEAR(l.at(t).acceleration, 0.0, 1e-7);
    // A cubic's it does, a little, most at the ends where the samples hold it on one side only.
    EXPECT_NEAR(c.at(t).value, 0.01 * t * t * t - 0.2 * t * t + t, 1e-4);
    EXPECT_NEAR(c.at(t).rate, 0.03 * t * t - 0.4 * t + 1.0, t > 0.5 && t < 9.5 ? 1e-3 : 4e-3);
  }
  // Outside its span it rests at its ends.
  EXPECT_NEAR(l.at(-1.0).value, 1.5, 1e-9);
  EXPECT_EQ(l.at(11.0).rate, 0.0);
  EXPECT_EQ(l.at(-1.0).acceleration, 0.0);
}

TEST(SmoothingSpline, ItsRatesAreTheDerivativesOfItsValues) {
  std::vector<double> times, values;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 0.3);
  for (int i = 0; i <= 40; ++i) {
    times.push_back(0.25 * i);
    values.push_back(noise(rng));
  }
  const UniformCubicSpline s = SmoothingSplineFit(times, 0.2, 1e-3).fit(values);
  const double h = 1e-5;
  for (double t = 0.01; t < 9.99; t += 0.0731) {
    EXPECT_NEAR(s.at(t).rate, (s.at(t + h).value - s.at(t - h).value) / (2 * h), 1e-5) << t;
    EXPECT_NEAR(s.at(t).acceleration, (s.at(t + h).rate - s.at(t - h).rate) / (2 * h), 1e-4) << t;
  }
}

// A walk round a circle of radius 3 m at 0.8 m/s, recorded at 10 Hz with 5 mm of noise, with a
// 5 s stop half-way round (slowing down and setting off over a second each, as a walker does).
constexpr double kRadius = 3.0, kSpeed = 0.8;
double lapTime() { return 2 * kPi * kRadius / kSpeed; }
double walkedAt(double t) {
  const double stop = 0.5 * lapTime();
  // Speed 0.8·w(t), w easing 1 → 0 over [stop − 1, stop] and 0 → 1 over [stop + 5, stop + 6];
  // the distance is its integral (the ease is a raised cosine, whose integral is closed form).
  auto eased = [](double u) {
    return 0.5 * u - std::sin(kPi * u) / (2 * kPi);
  };  // ∫ of (1−cos πu)/2
  if (t <= stop - 1.0) return kSpeed * t;
  if (t <= stop) return kSpeed * (stop - 1.0 + (1.0 - eased(1.0 - (t - (stop - 1.0)))) - 0.5);
  const double at_stop = kSpeed * (stop - 0.5);
  if (t <= stop + 5.0) return at_stop;
  if (t <= stop + 6.0) return at_stop + kSpeed * eased(t - stop - 5.0);
  return at_stop + kSpeed * (0.5 + t - stop - 6.0);
}

std::vector<bim::WalkPose> circleWalk(std::vector<Eigen::Vector2d>* truth = nullptr) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 0.005);
  std::vector<bim::WalkPose> walk;
  for (int i = 0; i <= int((lapTime() + 5.0) * 10); ++i) {
    const double t = 0.1 * i;
    const double angle = walkedAt(t) / kRadius;
    const Eigen::Vector2d p(kRadius * std::cos(angle), kRadius * std::sin(angle));
    if (truth != nullptr) truth->push_back(p);
    walk.push_back({t, p + Eigen::Vector2d(noise(rng), noise(rng)), 0.0, i + 1});
  }
  return walk;
}

TEST(WalkPath, FollowsARecordedWalkFacingTheWayAhead) {
  std::vector<Eigen::Vector2d> truth;
  const auto walk = circleWalk(&truth);
  const WalkPath path(walk, false, 1.2);
  EXPECT_NEAR(path.duration(), walk.back().t, 1e-12);
  // Through the noise: within a few millimetres of the true circle, nearer than the samples are.
  EXPECT_LT(path.medianDeviation(), 0.006);
  EXPECT_LT(path.maxDeviation(), 0.02);
  const double stop = 0.5 * lapTime();
  for (std::size_t i = 5; i + 5 < walk.size(); ++i) {
    const double t = walk[i].t;
    const WalkPath::State s = path.at(t);
    EXPECT_LT((s.xy - truth[i]).norm(), 0.01) << t;
    const bool stopped = t > stop + 0.5 && t < stop + 4.0;
    const bool walking = t < stop - 1.5 || t > stop + 6.5;
    if (walking) {
      // Along the tangent (counter-clockwise), at 0.8 m/s, swaying fully.
      const double tangent = std::atan2(truth[i].y(), truth[i].x()) + 0.5 * kPi;
      EXPECT_LT(std::abs(common::wrapAngle(s.yaw - tangent)), 3.0 * kPi / 180) << t;
      EXPECT_NEAR(s.velocity.norm(), kSpeed, 0.05) << t;
      EXPECT_GT(s.gait, 0.95) << t;
      // Turning at 0.8 / 3 rad/s over each second (the noise's jitter about it averages out).
      if (t > 1.0 && t + 1.0 < stop - 1.5) {
        EXPECT_NEAR(common::wrapAngle(path.at(t + 1.0).yaw - s.yaw), kSpeed / kRadius, 0.03) << t;
      }
    }
    if (stopped) {
      // Still but for the file's jitter, which does not sway it; it holds its heading.
      EXPECT_LT(s.velocity.norm(), 0.04) << t;
      EXPECT_LT(s.gait, 0.1) << t;
      EXPECT_LT(std::abs(s.yaw_rate), 0.03) << t;
    }
  }
}

TEST(WalkPath, TurnsNoFasterThanTheCarrierAndCanFaceTheFilesYaw) {
  // 3 m east, then straight back west: the way ahead flips by 180° at once.
  std::vector<bim::WalkPose> walk;
  for (int i = 0; i <= 120; ++i) {
    const double t = 0.1 * i;
    const double x = t < 6.0 ? 0.5 * t : 3.0 - 0.5 * (t - 6.0);
    walk.push_back({t, {x, 0.0}, 0.3, i + 1});
  }
  const WalkPath travel(walk, false, 0.8);
  double fastest = 0.0;
  for (double t = 0.0; t <= 12.0; t += 0.01)
    fastest = std::max(fastest, std::abs(travel.at(t).yaw_rate));
  // The heading's samples turn at 0.8 rad/s at most; the spline through them overshoots a little.
  EXPECT_LT(fastest, 0.8 * 1.15);
  EXPECT_GT(fastest, 0.5);
  EXPECT_NEAR(travel.at(1.0).yaw, 0.0, 0.02);
  EXPECT_NEAR(std::abs(common::wrapAngle(travel.at(11.5).yaw)), kPi, 0.02);
  // Facing the file's yaw instead: 0.3 rad throughout, walking backwards on the way back.
  const WalkPath file(walk, true, 0.8);
  for (double t = 0.0; t <= 12.0; t += 0.1) EXPECT_NEAR(file.at(t).yaw, 0.3, 1e-9) << t;
}

}  // namespace
}  // namespace isg::sim
