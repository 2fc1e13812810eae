#include "bim/polygon.hpp"

#include <gtest/gtest.h>

namespace isg::bim {
namespace {

const Polygon2 kSquare = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
// An L: the 2 × 2 square with its top-right 1 × 1 quarter removed.
const Polygon2 kEll = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};

TEST(Polygon, SignedAreaIsPositiveCounterClockwise) {
  EXPECT_DOUBLE_EQ(signedArea(kSquare), 4.0);
  EXPECT_DOUBLE_EQ(signedArea(Polygon2(kSquare.rbegin(), kSquare.rend())), -4.0);
  EXPECT_DOUBLE_EQ(signedArea(kEll), 3.0);
}

TEST(Polygon, CentroidOfAnEll) {
  // Two rectangles: [0,2]x[0,1] (area 2, centre (1, .5)) and [0,1]x[1,2] (area 1, centre
  // (.5, 1.5)).
  const Eigen::Vector2d c = centroid(kEll);
  EXPECT_NEAR(c.x(), (2 * 1.0 + 1 * 0.5) / 3.0, 1e-12);
  EXPECT_NEAR(c.y(), (2 * 0.5 + 1 * 1.5) / 3.0, 1e-12);
}

TEST(Polygon, ContainsPoint) {
  EXPECT_TRUE(containsPoint(kEll, {0.5, 0.5}));
  EXPECT_TRUE(containsPoint(kEll, {0.5, 1.5}));
  EXPECT_FALSE(containsPoint(kEll, {1.5, 1.5}));  // the missing quarter
  EXPECT_TRUE(containsPoint(kEll, {2.0, 0.5}));   // on the boundary
  EXPECT_FALSE(containsPoint(kEll, {-0.1, 0.5}));
}

TEST(Polygon, SimplePolygonsHaveNoSelfIntersection) {
  EXPECT_FALSE(findSelfIntersection(kSquare));
  EXPECT_FALSE(findSelfIntersection(kEll));
}

TEST(Polygon, BowTieCrossesItself) {
  const Polygon2 bowtie = {{0, 0}, {2, 2}, {2, 0}, {0, 2}};
  const auto crossing = findSelfIntersection(bowtie);
  ASSERT_TRUE(crossing);
  EXPECT_EQ(crossing->first, 0);
  EXPECT_EQ(crossing->second, 2);
}

TEST(Polygon, EdgeFoldingBackOntoItsNeighbourIsAnIntersection) {
  const Polygon2 folded = {{0, 0}, {2, 0}, {1, 0}, {1, 1}};
  EXPECT_TRUE(findSelfIntersection(folded));
}

TEST(Polygon, TouchingAVertexIsAnIntersection) {
  // Vertex 4 lies on edge 0 → 1.
  const Polygon2 touching = {{0, 0}, {4, 0}, {4, 2}, {2, 2}, {2, 0.0}, {0, 2}};
  EXPECT_TRUE(findSelfIntersection(touching));
}

TEST(Polygon, DistanceToSegment) {
  EXPECT_DOUBLE_EQ(distanceToSegment({1, 1}, {0, 0}, {2, 0}), 1.0);
  EXPECT_DOUBLE_EQ(distanceToSegment({3, 0}, {0, 0}, {2, 0}), 1.0);
  EXPECT_DOUBLE_EQ(distanceToSegment({-3, 4}, {0, 0}, {2, 0}), 5.0);
}

}  // namespace
}  // namespace isg::bim
