#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/angles.hpp"
#include "slam/sgraph/plane_extraction.hpp"
#include "slam/sgraph/plane_fit.hpp"

namespace isg::slam {
namespace {

// A ring scan's points on the wall y = h from x0 to x1, from a sensor at the origin: one column of
// points per azimuth step (`step_deg`) at each ring's height (16 rings, −15° … 15°) that falls
// between the floor 0.6 m below the sensor and the ceiling 2.4 m above it.
void wallColumns(double h, double x0, double x1, double step_deg,
                 std::vector<Eigen::Vector3d>& out) {
  const double a0 = std::atan2(h, x1), a1 = std::atan2(h, x0);
  for (double a = a0; a <= a1; a += common::radians(step_deg)) {
    const double x = h / std::tan(a), range = std::hypot(x, h);
    for (int ring = 0; ring < 16; ++ring) {
      const double z = range * std::tan(common::radians(-15.0 + 2.0 * ring));
      if (z > -0.6 && z < 2.4) out.emplace_back(x, h, z);
    }
  }
}

TEST(PlanePieces, AWallBuiltInTwoPartsIsTwoPiecesThoughACeilingArcLiesInItsPlaneAcrossTheGap) {
  // Parts x ∈ [−3, −0.5] and [1, 3] of the wall y = 3; across the gap, the top ring meets the
  // ceiling along an arc tangent to the wall's line: points in the wall's plane at one height.
  std::vector<Eigen::Vector3d> points;
  wallColumns(3.0, -3.0, -0.5, 0.2, points);
  wallColumns(3.0, 1.0, 3.0, 0.2, points);
  for (double x = -0.5; x <= 1.0; x += 0.03) points.emplace_back(x, 3.0 + 0.01 * std::cos(x), 2.4);
  const PlaneExtractionOptions options;
  const PlaneObservation wall = observePlane(points, int(points.size()), options);
  ASSERT_EQ(wall.orientation, PlaneOrientation::kVertical);
  const double x_start = wall.start.x(), x_end = wall.end.x();
  ASSERT_EQ(wall.pieces.size(), 2u);
  // Back to x along the wall (start → end may run either way).
  const auto x_at = [&](double share) { return x_start + share * (x_end - x_start); };
  const double a0 = std::min(x_at(wall.pieces[0].first), x_at(wall.pieces[0].second));
  const double a1 = std::max(x_at(wall.pieces[0].first), x_at(wall.pieces[0].second));
  const double b0 = std::min(x_at(wall.pieces[1].first), x_at(wall.pieces[1].second));
  const double b1 = std::max(x_at(wall.pieces[1].first), x_at(wall.pieces[1].second));
  const double lo0 = std::min(a0, b0), hi0 = a0 < b0 ? a1 : b1;
  const double lo1 = a0 < b0 ? b0 : a0, hi1 = std::max(a1, b1);
  EXPECT_NEAR(lo0, -3.0, 0.05);
  EXPECT_NEAR(hi0, -0.5, 0.05);
  EXPECT_NEAR(lo1, 1.0, 0.05);
  EXPECT_NEAR(hi1, 3.0, 0.05);
}

TEST(PlanePieces, AWallWholeIsOnePieceEvenWhereItIsSampledSparselyFarOff) {
  // The wall y = 1 from x = 2 to 25 seen at a grazing angle: at x = 25 the 0.2° azimuth steps
  // fall 2.2 m apart along it, farther than cluster_tolerance, not a hole.
  std::vector<Eigen::Vector3d> points;
  wallColumns(1.0, 2.0, 25.0, 0.2, points);
  const PlaneObservation wall = observePlane(points, int(points.size()), PlaneExtractionOptions{});
  ASSERT_EQ(wall.orientation, PlaneOrientation::kVertical);
  EXPECT_NEAR(std::abs(wall.end.x() - wall.start.x()), 23.0, 0.5);
  EXPECT_TRUE(wall.pieces.empty());
}

TEST(PlanePieces, AWallWithAGapTheSamplingCannotExplainIsTwoPieces) {
  // The same wall with x ∈ [4, 5.5] not built: 1.5 m, where the 0.2° steps fall 0.1 m apart and
  // two of the range image's 0.8° columns span 0.9 m.
  std::vector<Eigen::Vector3d> points;
  wallColumns(1.0, 2.0, 4.0, 0.2, points);
  wallColumns(1.0, 5.5, 25.0, 0.2, points);
  const PlaneObservation wall = observePlane(points, int(points.size()), PlaneExtractionOptions{});
  ASSERT_EQ(wall.pieces.size(), 2u);
  const double length = std::abs(wall.end.x() - wall.start.x());
  EXPECT_NEAR((wall.pieces[1].first - wall.pieces[0].second) * length, 1.5, 0.15);
}

}  // namespace
}  // namespace isg::slam
