#include "slam/sgraph/confirmed_spans.hpp"

#include <gtest/gtest.h>

namespace isg::slam {
namespace {

using Spans = std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>;

// A map wall along x from 0 to `length`, and spans along it [a, b] (metres from its start).
MapPlane wallAlongX(double length, int observations) {
  MapPlane m;
  m.start = Eigen::Vector2d(0.0, 2.0);
  m.end = Eigen::Vector2d(length, 2.0);
  m.observations = observations;
  return m;
}

void addSpan(Spans& spans, double a, double b) {
  spans.push_back({Eigen::Vector2d(a, 2.0), Eigen::Vector2d(b, 2.0)});
}

TEST(ConfirmedSpans, TwoStraysPastAWallsEndDoNotStretchIt) {
  // 30 observations of a part ending between 2.13 and 2.16 m (as the map saw it end); two that ran
  // past it, to 2.21 and 2.37 m (a keyframe a few degrees off). Two agreeing past 2.16 would have
  // confirmed it to 2.21.
  Spans spans;
  for (int k = 0; k < 30; ++k) addSpan(spans, 0.02 * (k % 5), 2.13 + 0.001 * k);
  addSpan(spans, 0.1, 2.21);
  addSpan(spans, 0.2, 2.37);
  const auto confirmed = confirmedSpans(wallAlongX(5.0, 32), spans);
  ASSERT_EQ(confirmed.size(), 1u);
  EXPECT_NEAR(confirmed[0].first, 0.04, 1e-9);  // the median of where they start
  EXPECT_GE(confirmed[0].second, 2.13);
  EXPECT_LE(confirmed[0].second, 2.16);
}

TEST(ConfirmedSpans, AGapsEdgesAreWhereHalfTheObservationsEndNotAFifth) {
  // A wall with a gap from 2 to 3 m. 49 observations see each part to the gap, their ends spread
  // evenly over ±3 cm (their keyframes' errors); 10 more stop 0.3 m short of the first edge (an
  // occluder). Where a fifth of them still reach, the edges would lie 1.8 cm into the gap; the
  // median of the ends near each is where the gap is, the occluded ten pulling the first in 6 mm.
  Spans spans;
  for (int k = 0; k < 49; ++k) {
    const double spread = -0.03 + 0.06 * k / 48.0;
    addSpan(spans, 0.0, 2.0 + spread);
    addSpan(spans, 3.0 + spread, 6.0);
  }
  for (int k = 0; k < 10; ++k) addSpan(spans, 0.0, 1.7);
  const auto confirmed = confirmedSpans(wallAlongX(6.0, 108), spans);
  ASSERT_EQ(confirmed.size(), 2u);
  EXPECT_NEAR(confirmed[0].first, 0.0, 1e-9);
  EXPECT_NEAR(confirmed[0].second, 2.0 - 0.006, 0.001);
  EXPECT_NEAR(confirmed[1].first, 3.0, 1e-6);
  EXPECT_NEAR(confirmed[1].second, 6.0, 1e-9);
}

TEST(ConfirmedSpans, APartSeenByFewBesideOneSeenByManyLosesOnlyHalfAMetre) {
  // 20 observations of [0, 4]; 3 of [3.5, 10] (far, or past an occluder). Beyond 0.5 m of the
  // well-seen part, three agree: confirmed.
  Spans spans;
  for (int k = 0; k < 20; ++k) addSpan(spans, 0.0, 4.0);
  for (int k = 0; k < 3; ++k) addSpan(spans, 3.5, 10.0);
  const auto confirmed = confirmedSpans(wallAlongX(10.0, 23), spans);
  ASSERT_EQ(confirmed.size(), 2u);
  EXPECT_NEAR(confirmed[0].first, 0.0, 1e-9);
  EXPECT_NEAR(confirmed[0].second, 4.0, 1e-9);
  EXPECT_NEAR(confirmed[1].first, 4.5, 1e-9);
  EXPECT_NEAR(confirmed[1].second, 10.0, 1e-9);
}

TEST(ConfirmedSpans, AWallSeenByFewIsConfirmedWhereTwoAgree) {
  // A long wall seen a few times along its length, each part by two or three: confirmed where two
  // overlap, and a gap that none saw stays a gap.
  Spans spans;
  addSpan(spans, 0.0, 6.0);
  addSpan(spans, 1.0, 8.0);
  addSpan(spans, 5.0, 8.0);
  addSpan(spans, 9.0, 12.0);
  addSpan(spans, 9.5, 12.0);
  const auto confirmed = confirmedSpans(wallAlongX(12.0, 5), spans);
  ASSERT_EQ(confirmed.size(), 2u);
  EXPECT_NEAR(confirmed[0].first, 1.0, 1e-9);
  EXPECT_NEAR(confirmed[0].second, 8.0, 1e-9);
  EXPECT_NEAR(confirmed[1].first, 9.5, 1e-9);
  EXPECT_NEAR(confirmed[1].second, 12.0, 1e-9);
}

TEST(ConfirmedSpans, AWallSeenOnceIsConfirmedWhereItWasSeenAndTheSpansAreClampedToTheWall) {
  Spans spans;
  addSpan(spans, -0.5, 3.0);
  const auto confirmed = confirmedSpans(wallAlongX(4.0, 1), spans);
  ASSERT_EQ(confirmed.size(), 1u);
  EXPECT_NEAR(confirmed[0].first, 0.0, 1e-9);
  EXPECT_NEAR(confirmed[0].second, 3.0, 1e-9);
}

}  // namespace
}  // namespace isg::slam
